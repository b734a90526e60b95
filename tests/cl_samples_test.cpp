// The real CL files in ../shared/cl-samples, read from disk through file_source. The files
// are not part of the project: when the folder is absent every test here is skipped
// (tests/shared_samples.hpp).
#include <catch2/catch.hpp>

#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "parser/cl_reader.hpp"
#include "parser/event_text.hpp"
#include "parser_test_support.hpp"
#include "tests/shared_samples.hpp"

using namespace twinpost;
namespace fs = std::filesystem;

namespace {

const fs::path samples_dir = test::shared_samples_dir();

struct sample_result : test::read_result {
  std::string path;

  // How many events have this name ("arc", "goto", ...), optionally with a word in them.
  int count(const std::string& name, const std::string& with = "") const {
    int n = 0;
    for (const std::string& e : events) {
      std::size_t tab = e.find('\t');
      std::string rest = e.substr(tab + 1);
      if (rest.compare(0, name.size() + 1, name + " ") != 0 && rest != name) continue;
      if (!with.empty() && rest.find(with) == std::string::npos) continue;
      ++n;
    }
    return n;
  }
  bool has(const std::string& line) const {
    for (const std::string& e : events)
      if (e == line) return true;
    return false;
  }
};

sample_result read_sample(const fs::path& p) {
  const std::string path = p.string();
  std::FILE* f = std::fopen(path.c_str(), "rb");
  REQUIRE(f != nullptr);
  file_source src(f);
  cl_reader_options options;
  options.file_name = path;
  sample_result r{test::read_source(src, options, false), path};
  std::fclose(f);
  return r;
}

sample_result read_named(const std::string& relative) { return read_sample(samples_dir / relative); }

}  // namespace

TEST_CASE("every sample file reads without an error", "[samples]") {
  test::require_shared_samples();
  std::vector<fs::path> files;
  for (const auto& family : fs::directory_iterator(samples_dir)) {
    if (!family.is_directory()) continue;
    for (const auto& f : fs::directory_iterator(family.path()))
      if (f.is_regular_file() && f.path().filename() != "README.md") files.push_back(f.path());
  }
  CHECK(files.size() >= 16);
  for (const fs::path& p : files) {
    if (p.filename() == "aamorim_Interface-glue.clt") continue;  // its one error: see below
    sample_result r = read_sample(p);
    INFO(r.path);
    CHECK(r.diagnostics == "");
    CHECK(r.events.size() > 10);
  }
}

TEST_CASE("the .clt sample has exactly one error: blanks instead of commas", "[samples]") {
  test::require_shared_samples();
  sample_result r = read_named("solidworks-cam/aamorim_Interface-glue.clt");
  CHECK(r.errors == 1);
  CHECK(r.warnings == 0);
  CHECK(r.diagnostics ==
        r.path +
            ":12:89: error: expected ',' between arguments, found '46.927686'\n"
            "CYCLE/ DRILL,G98,12.373300,PECKING,5.000000,2.000000,MMPM,187.165839,3.000000,"
            "46.927686 46.927686 DWELL,0.000000 \n"
            "                                                                                        ^\n");
  // Reading went on: the rest of the file is there, explicit arc directions included.
  CHECK(r.count("arc") == 30);
  CHECK(r.count("arc", "dir=cw") == 9);
  CHECK(r.count("arc", "dir=ccw") == 21);
  CHECK(r.has("2134\tarc x=67.5 y=3 z=-19.5 cx=67.5 cy=67.5 cz=-19.5 i=0 j=0 k=1 r=64.5 dir=cw"));
  CHECK(r.has("4\ttool-axis i=0 j=-1 k=0"));
  CHECK(r.has("7\tpassthrough major=ROTABL args=0,BAXIS,TABLE,CCLW"));
}

TEST_CASE("dialect detection on each sample family", "[samples]") {
  test::require_shared_samples();
  const std::map<std::string, dialect> expected = {
      {"creo/nist_v18_gg.ncl", dialect::creo},
      {"creo/nist_v18_traj1.ncl", dialect::creo},
      {"creo/nist_v18_conv_key.ncl", dialect::creo},
      {"creo/creopost_bohren_1.ncl.8", dialect::creo},
      {"creo/creopost_profilfraesen_2.ncl.1", dialect::creo},
      {"nx/stepnode_simple_block.cls", dialect::nx},
      {"catia/trajcenter_PrepaFlans_Pointage.aptsource", dialect::catia},
      {"makino-ffcam/stepnode_Plane_1.cldata", dialect::makino},
      {"makino-ffcam/stepnode_Plane_2.cldata", dialect::makino},
      {"solidworks-cam/aamorim_Dem-target1.apt", dialect::solidworks},
      {"solidworks-cam/aamorim_Interface-glue.clt", dialect::solidworks},
      {"solidworks-cam/aamorim_Paralelipipedo-furos.apt", dialect::solidworks},
      {"solidworks-cam/aamorim_RotateThin.apt", dialect::solidworks},
      {"solidworks-cam/aamorim_Suporte-parede-side-drill.apt", dialect::solidworks},
      {"solidworks-cam/aamorim_Teste-Metrologia.apt", dialect::solidworks},
      {"solidworks-cam/aamorim_lateral-leg-holder.apt", dialect::solidworks},
  };
  for (const auto& [file, d] : expected) {
    INFO(file);
    CHECK(dialect_name(read_named(file).used) == dialect_name(d));
  }
}

TEST_CASE("Creo arcs are ccw, NX and Makino arcs are cw (pitfall 1)", "[samples]") {
  test::require_shared_samples();
  sample_result creo = read_named("creo/creopost_profilfraesen_2.ncl.1");
  CHECK(creo.count("arc") == 20);
  CHECK(creo.count("arc", "dir=ccw") == 20);
  CHECK(creo.has("20\tarc x=1.5 y=0 z=-1.5 cx=0 cy=0 cz=-1.5 i=0 j=0 k=-1 r=1.5 dir=ccw"));

  sample_result nx = read_named("nx/stepnode_simple_block.cls");
  CHECK(nx.count("arc") == 33);
  CHECK(nx.count("arc", "dir=cw") == 33);
  CHECK(nx.has("24\tarc x=102.0069 y=105.9992 z=20 cx=90.0336 cy=90.112 cz=20 i=0 j=0 k=1 r=19.8938 dir=cw"));

  sample_result makino = read_named("makino-ffcam/stepnode_Plane_1.cldata");
  CHECK(makino.count("arc", "dir=cw") == 29);
  CHECK(makino.count("arc", "dir=ccw") == 0);
}

TEST_CASE("Creo samples: multi-point GOTO on a circle, $$-> records, cycles", "[samples]") {
  test::require_shared_samples();
  sample_result gg = read_named("creo/nist_v18_gg.ncl");
  CHECK(gg.count("arc") == 6);
  CHECK(gg.count("arc", "continued") == 4);
  CHECK(gg.has("23\tarc x=7.43 y=5.85 z=1.8 cx=7.455 cy=5.85 cz=1.8 i=0 j=0 k=1 r=0.025 dir=ccw continued"));
  CHECK(gg.has("6\tunits units=inch"));
  CHECK(gg.has("13\tgoto x=7.43 y=5.85 z=3.775 rapid"));
  CHECK(gg.has("38\tend word=FINI"));

  sample_result bohren = read_named("creo/creopost_bohren_1.ncl.8");
  CHECK(bohren.has("10\tcoordsys from=\"$$-> CSYS\" values=1,0,0,0,0,1,0,0,0,0,1,0"));
  CHECK(bohren.has("16\tcycle type=DEEP DEPTH=3.5 STEP=1 MMPM=50 CLEAR=1"));
  CHECK(bohren.has("13\tspindle mode=rpm speed=9000 dir=cw"));
  CHECK(bohren.count("cycle") == 2);
}

TEST_CASE("NX sample: modal tool axis, one FEDRAT, many RAPIDs, END-OF-PATH", "[samples]") {
  test::require_shared_samples();
  sample_result nx = read_named("nx/stepnode_simple_block.cls");
  CHECK(nx.count("goto") == 71);
  CHECK(nx.count("goto", " rapid") == 30);
  CHECK(nx.count("goto", "i=0 j=0 k=1") == 71);  // axis given once, carried on every point
  CHECK(nx.count("feed") == 1);
  CHECK(nx.has("7\tspindle mode=rpm speed=1000 dir=cw"));
  CHECK(nx.has("207\tend word=END-OF-PATH"));
}

TEST_CASE("CATIA sample: matrix, ISO-8859-1 comments, positional cycles, END", "[samples]") {
  test::require_shared_samples();
  sample_result catia = read_named("catia/trajcenter_PrepaFlans_Pointage.aptsource");
  CHECK(catia.has("7\tcoordsys from=$$*CATIA0 values=1,0,0,-220,0,1,0,-170,0,0,1,20"));
  CHECK(catia.has("2\tcomment text=\"G\\u00e9n\\u00e9r\\u00e9 le jeudi 30 novembre 2023 08:46:00\""));
  CHECK(catia.has("29\tspindle mode=rpm speed=2546.479 dir=cw"));
  CHECK(catia.count("cycle", "type=DRILL values=3,5") == 12);
  CHECK(catia.count("cycle", "type=OFF") == 12);
  CHECK(catia.has("145\tend word=END"));
}

TEST_CASE("SolidWorks samples: 6-value CIRCLE radius, CRLF file", "[samples]") {
  test::require_shared_samples();
  sample_result leg = read_named("solidworks-cam/aamorim_lateral-leg-holder.apt");
  CHECK(leg.count("arc", "dir=ccw") == 8);
  CHECK(
      leg.has("23\tarc x=224.316625 y=-4.336675 z=-6 cx=224.97995 cy=-5.336675 cz=-6 i=0 j=0 k=1 "
              "r=1.1999996092203538 dir=ccw"));
  sample_result crlf = read_named("solidworks-cam/aamorim_Teste-Metrologia.apt");
  CHECK(crlf.count("arc") == 65);
  CHECK(crlf.has("780\tend word=FINI"));
}
