// cl_generate: writes large, deterministic CL jobs for benchmarking twinpost.
//
//   cl_generate --kind mill3|mill5|lathe2 --records N [--seed S] [-o FILE]
//
// The same arguments give the same bytes on every run (see bench/cl_writer.hpp). N is the
// exact number of logical CL records, and every record is one line, so `wc -l` prints N.
// Output streams through a 1 MiB buffer: 10^7 records need no more memory than 10^3. With
// -o the job is written to FILE.part and renamed at the end, so an interrupted run never
// leaves a truncated FILE behind.
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <string>
#include <string_view>

#include "cl_writer.hpp"
#include "lathe_job.hpp"
#include "mill_job.hpp"

namespace {

const char* const usage =
    "usage: cl_generate --kind mill3|mill5|lathe2 --records N [--seed S] [-o FILE]\n"
    "  --kind     mill3: NX-style 3-axis raster (GOTO/x,y,z, CIRCLE, RAPID)\n"
    "             mill5: NX-style 5-axis (MULTAX, GOTO/x,y,z,i,j,k)\n"
    "             lathe2: twin-turret lathe (HEAD/1, HEAD/2, TURRET, SYNC/k,1,2)\n"
    "  --records  exact number of CL records (= lines); 1e6 style is accepted\n"
    "  --seed     random seed (default 1)\n"
    "  -o FILE    write FILE instead of standard output\n";

// A count written as 1000000, 1e6 or 2.5e5.
bool parse_count(std::string_view s, std::uint64_t& out) {
  double v = 0;
  auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size() || !(v >= 1) || v > 1e12) return false;
  out = static_cast<std::uint64_t>(v);
  return static_cast<double>(out) == v;
}

int fail(const std::string& message) {
  std::fprintf(stderr, "cl_generate: %s\n", message.c_str());
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::string kind, output;
  std::uint64_t records = 0, seed = 1;
  for (int i = 1; i < argc; ++i) {
    std::string_view a = argv[i];
    bool has_value = i + 1 < argc;
    if (a == "-h" || a == "--help") {
      std::fputs(usage, stdout);
      return 0;
    } else if (a == "--kind" && has_value) {
      kind = argv[++i];
    } else if (a == "--records" && has_value) {
      if (!parse_count(argv[++i], records)) return fail(std::string("bad --records '") + argv[i] + "'");
    } else if (a == "--seed" && has_value) {
      if (!parse_count(argv[++i], seed)) return fail(std::string("bad --seed '") + argv[i] + "'");
    } else if (a == "-o" && has_value) {
      output = argv[++i];
    } else {
      std::fputs(usage, stderr);
      return 2;
    }
  }
  if (kind != "mill3" && kind != "mill5" && kind != "lathe2") {
    std::fputs(usage, stderr);
    return 2;
  }
  std::uint64_t minimum =
      kind == "lathe2" ? bench::lathe_job::minimum_records : bench::mill_job::minimum_records;
  if (records < minimum)
    return fail("--records must be at least " + std::to_string(minimum) + " for " + kind);

  std::string part = output + ".part";
  std::FILE* out = stdout;
  if (!output.empty()) {
    out = std::fopen(part.c_str(), "wb");
    if (!out) return fail("cannot write '" + part + "'");
  }
  try {
    {
      bench::record_writer w(out);
      bench::random_source rng(seed);
      if (kind == "lathe2") {
        bench::lathe_job(w, rng).write(records, seed);
      } else {
        bench::mill_job(w, rng, kind == "mill5").write(records, seed);
      }
      w.flush();
      if (w.records() != records) throw std::runtime_error("internal error: record count is off");
    }
    if (std::fflush(out) != 0) throw std::runtime_error("write failed");
  } catch (const std::exception& e) {
    if (!output.empty()) {
      std::fclose(out);
      std::remove(part.c_str());
    }
    return fail(e.what());
  }
  if (!output.empty()) {
    if (std::fclose(out) != 0 || std::rename(part.c_str(), output.c_str()) != 0) {
      std::remove(part.c_str());
      return fail("cannot write '" + output + "'");
    }
  }
  return 0;
}
