// Inch output (program.output_units = "inch"): every length, feed and surface speed in the
// program's units, whatever the CL's, and a header that tells the control (G20).
#include <catch2/catch.hpp>

#include <string>

#include "file_test_support.hpp"
#include "machine_test_support.hpp"
#include "machines/machine_loader.hpp"
#include "post_test_jobs.hpp"

using namespace twinpost;

namespace {

// The 0i-TD built-in in inch: G20 in the header, the inch word formats (X 4.4, F 4.5).
machine inch_lathe() {
  machine m = load_machine("fanuc-0itd-twin");
  m.program.output_units = output_unit::inch;
  m.program.header = {"G0 G18 G20 G40 G54 G80 G99"};
  m.formats = default_word_formats(m.control, true);
  return m;
}

// A diameter of 50.8 mm (2 in), CSS 200 m/min, 0.2 mm/rev, an arc of 10 mm radius, 500 mm/min.
const std::string mm_job =
    "PARTNO INCH\nUNITS/MM\nTURRET/1,1\nSPINDL/SMM,200,MAXRPM,3000,CLW\nFEDRAT/0.2,MMPR\nRAPID\n"
    "GOTO/25.4,0,2.54\nGOTO/25.4,0,-50.8\nCIRCLE/25.4,0,-60.8,0,1,0,10\nGOTO/35.4,0,-60.8\n"
    "FEDRAT/500,MMPM\nGOTO/40,0,-60.8\nFINI\n";

const std::string inch_program =
    "%\nO1000 (INCH)\nG0 G18 G20 G40 G54 G80 G99\nG28 U0.\nG28 W0.\nT0101\nG50 S3000\nG96 S656 M3\n"
    "G0 X2. Z0.1\nG1 Z-2. F0.00787\nG3 X2.7874 Z-2.3937 I0. K-0.3937\nG98\nG1 X3.1496 F19.69\nM100\nM9\n"
    "G28 U0.\nG28 W0.\nM5\nM30\n%\n";

std::string program_of(const std::string& cl, const machine& m, const std::string& tag) {
  const test::posted p = test::post_in_fresh_dir(
      cl, m, "units-" + tag, [](const diagnostic& d) { return d.level == severity::error; });
  if (!p.ok) return "(failed)\n" + p.diagnostics;
  const auto f = p.files.find("INCH_1.nc");
  return f == p.files.end() ? "(missing)" : f->second;
}

}  // namespace

TEST_CASE("inch output writes lengths, feeds and surface speed in inches", "[post][units]") {
  CHECK(program_of(mm_job, inch_lathe(), "mm-cl") == inch_program);
}

TEST_CASE("an inch CL posted in inch gives the same program as its mm twin", "[post][units]") {
  const std::string inch_job =
      "PARTNO INCH\nUNITS/INCHES\nTURRET/1,1\nSPINDL/SFM,656.168,MAXRPM,3000,CLW\nFEDRAT/0.00787402,IPR\n"
      "RAPID\nGOTO/1,0,0.1\nGOTO/1,0,-2\nCIRCLE/1,0,-2.3937008,0,1,0,0.3937008\nGOTO/1.3937008,0,-2.3937008\n"
      "FEDRAT/19.685039,IPM\nGOTO/1.5748031,0,-2.3937008\nFINI\n";
  CHECK(program_of(inch_job, inch_lathe(), "inch-cl") == inch_program);
}

TEST_CASE("the header must tell the control the output units", "[machines][units]") {
  const std::string channels = test::two_channels;
  CHECK(test::machine_error_of(test::machine_head +
                               "[program]\noutput_units = \"inch\"\nheader = [\"G0 G21\"]\n" + channels) ==
        "m.toml:8:10: error: program.header writes G21 (millimetres) but program.output_units is inch");
  CHECK(test::machine_error_of(test::machine_head +
                               "[program]\noutput_units = \"inch\"\nheader = [\"G0 G18\"]\n" + channels) ==
        "m.toml:8:10: error: program.output_units = inch needs G20 in program.header");
  CHECK(test::machine_error_of(test::machine_head + "[program]\nheader = [\"G20 G0\"]\n" + channels) ==
        "m.toml:7:10: error: program.header writes G20 (inches) but program.output_units is mm");
  CHECK(test::machine_error_of(test::machine_head + "[program]\noutput_units = \"feet\"\n" + channels) ==
        "m.toml:7:16: error: program.output_units must be mm or inch, not 'feet'");
  // Inch output reads its axis words with four decimals: the defaults are 4.4.
  const machine m = parse_machine(
      test::machine_head + "[program]\noutput_units = \"inch\"\nheader = [\"G20\"]\n" + channels, "m.toml");
  CHECK(m.formats['X'].text() == "4.4");
  CHECK(m.formats['F'].text() == "4.5");
  CHECK(test::machine_error_of(
            test::machine_head +
            "[program]\noutput_units = \"inch\"\nheader = [\"G20\"]\n[format]\nZ = \"5.3\"\n" + channels) ==
        "m.toml:10:5: error: format.Z (5.3) has fewer decimals than "
        "program.decimals_inch (4)");
}
