// twinpost post JOB --machine M -o DIR [--layout L] [--sync P]: post a CL job.
#include <boost/program_options.hpp>
#include <chrono>
#include <filesystem>
#include <unistd.h>
#include <fmt/format.h>

#include "cli/cli_util.hpp"
#include "cli/commands.hpp"
#include "cli/interrupt.hpp"
#include "post/post_job.hpp"
#include "cli/machine_dirs.hpp"
#include "machines/layout_rules.hpp"

namespace twinpost::cli {

namespace po = boost::program_options;

int run_post(const args& a) {
  po::options_description opts("twinpost post JOB --machine M -o DIR [options]");
  opts.add_options()("help,h", "show this help")("machine,m", po::value<std::string>(), "machine name or TOML file")(
      "output,o", po::value<std::string>(), "output folder (made if missing)")(
      "layout", po::value<std::string>(), "split|merged-appended|merged-sections (default: the machine's)")(
      "sync", po::value<std::string>()->default_value("auto"), "explicit|sequential|auto")(
      "dialect", po::value<std::string>(), "CL dialect (default: detect)")("job", po::value<std::string>(), "CL file");
  po::positional_options_description pos;
  pos.add("job", 1);
  po::variables_map vm;
  if (!parse_options(a, opts, pos, vm, "post")) return 2;
  if (vm.count("help")) {
    fmt::print("{}", to_string(opts));
    return 0;
  }
  for (const char* need : {"job", "machine", "output"}) {
    if (!vm.count(need)) {
      fmt::print(stderr, "twinpost post: missing {}\n", std::string(need) == "job" ? "CL job file" : fmt::format("--{}", need));
      return 2;
    }
  }
  post_options o;
  o.cl_path = vm["job"].as<std::string>();
  o.out_dir = vm["output"].as<std::string>();
  std::string sync = vm["sync"].as<std::string>();
  if (sync == "explicit") o.policy = sync_policy::explicit_marks;
  else if (sync == "sequential") o.policy = sync_policy::sequential;
  else if (sync == "auto") o.policy = sync_policy::automatic;
  else {
    fmt::print(stderr, "twinpost post: --sync must be explicit, sequential or auto\n");
    return 2;
  }
  if (vm.count("layout")) {
    std::string l = vm["layout"].as<std::string>();
    if (l == "split") o.layout = layout_kind::split;
    else if (l == "merged-appended") o.layout = layout_kind::merged_appended;
    else if (l == "merged-sections") o.layout = layout_kind::merged_sections;
    else {
      fmt::print(stderr, "twinpost post: --layout must be split, merged-appended or merged-sections\n");
      return 2;
    }
  }
  if (vm.count("dialect")) {
    o.forced_dialect = dialect_from_name(vm["dialect"].as<std::string>());
    if (!o.forced_dialect) {
      fmt::print(stderr, "twinpost post: unknown dialect '{}'\n", vm["dialect"].as<std::string>());
      return 2;
    }
  }
  const located_machine found = locate_machine(vm["machine"].as<std::string>());
  const machine& m = found.def;
  if (const std::string why = layout_problem(m, o.layout.value_or(m.layout)); !why.empty()) {
    fmt::print(stderr, "twinpost post: --layout: machine '{}': {}\n", m.name, why);
    return 2;
  }
  // Progress on stderr only for a person watching a terminal: never in logs or pipes.
  std::error_code ec;
  const auto total = std::filesystem::file_size(o.cl_path, ec);
  bool shown = false;
  if (!ec && ::isatty(2)) {
    auto last = std::chrono::steady_clock::now();
    o.progress = [&, total](std::size_t bytes) {
      auto now = std::chrono::steady_clock::now();
      if (now - last < std::chrono::milliseconds(250)) return;
      last = now;
      shown = true;
      fmt::print(stderr, "\rpost: {:3}% of {} MB", total ? bytes * 100 / total : 100, total >> 20);
    };
  }
  printing_sink sink;
  install_interrupt_cleanup();
  post_summary s = post_job(o, m, sink);
  if (shown) fmt::print(stderr, "\r{:30}\r", "");
  if (!s.ok) {
    fmt::print(stderr, "post: failed with {} error{}; no file written\n", sink.errors(), sink.errors() == 1 ? "" : "s");
    return 1;
  }
  // One channel waits for nobody: no policy to report.
  const std::string waits = s.channels == 1 ? "no waits (one channel)"
                            : fmt::format("{} waits ({})", s.waits,
                                          s.policy == sync_policy::explicit_marks ? "explicit" : "sequential");
  fmt::print("post: {} records, {} channel{}, {} blocks, {}, {} warning{}\n", s.records, s.channels,
             s.channels == 1 ? "" : "s", s.blocks, waits, sink.warnings(), sink.warnings() == 1 ? "" : "s");
  fmt::print("  machine {} ({})\n", m.name, found.origin);
  for (const std::string& f : s.files) fmt::print("  wrote {}\n", f);
  return 0;
}

}  // namespace twinpost::cli
