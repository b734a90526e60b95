// twinpost timeline: the cycle time of NC programs, and the page that shows it.
#include <boost/program_options.hpp>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "analysis/cycle_time.hpp"
#include "analysis/timeline_report.hpp"
#include "check/nc_input.hpp"
#include "cli/cli_util.hpp"
#include "cli/command_table.hpp"
#include "cli/commands.hpp"
#include "cli/machine_dirs.hpp"
#include "support/errors.hpp"

namespace twinpost::cli {

namespace {

std::string timeline_usage() {
  return "usage: " + command_usage("timeline") +
         "\n"
         "\n"
         "Times every block of NC programs that check sound, runs the channels together and\n"
         "prints the cycle time, each channel's idle at its waits and where to balance; -o\n"
         "writes the timeline as one HTML page, --json prints the data for tools.\n"
         "Exit status: 0 timed, 1 the programs do not check sound, 2 usage or configuration error.\n"
         "\n";
}

bool write_file(const std::string& path, const std::string& text) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return false;
  const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  return std::fclose(f) == 0 && ok;
}

}  // namespace

int run_timeline(const args& a) {
  namespace po = boost::program_options;
  po::options_description opts("options");
  opts.add_options()("help,h", "show this help")("machine,m", po::value<std::string>(),
                                                 "built-in machine name or machine file (required)")(
      "output,o", po::value<std::string>(), "write the timeline page (one HTML file) here")(
      "json", "print the timeline as one JSON object instead of the summary");
  po::options_description all;
  all.add(opts).add_options()("file", po::value<std::vector<std::string>>(), "NC files");
  po::positional_options_description pos;
  pos.add("file", -1);
  po::variables_map vm;
  if (const std::optional<int> done =
          parse_command(a, all, pos, vm, "timeline", timeline_usage() + to_string(opts)))
    return *done;
  if (!vm.count("file")) {
    fmt::print(stderr, "twinpost timeline: missing NC files\n");
    return 2;
  }
  if (!vm.count("machine")) {
    fmt::print(stderr, "twinpost timeline: missing --machine\n");
    return 2;
  }
  const machine m = locate_machine(vm["machine"].as<std::string>()).def;
  if (!has_timing(m)) {
    print_error(
        fmt::format("machine '{}' has no [timing] table: give its rapid rates and tool-change time "
                    "(docs/machines.md, \"[timing]\")",
                    m.name));
    return 2;
  }
  std::vector<nc_source> sources;
  for (const std::string& path : vm["file"].as<std::vector<std::string>>()) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec) || !std::filesystem::exists(path, ec)) {
      print_error(fmt::format("cannot read '{}'", path));
      return 2;
    }
    sources.push_back({path, {}, path});
  }
  // A pipe is copied once here: --json reads the programs a second time for their blocks.
  sources = rereadable(sources);
  timeline_options o;
  o.keep_blocks = vm.count("output") > 0;  // the page; --json streams its blocks by a reading of its own
  const timeline t = make_timeline(sources, m, o);
  printing_sink sink;
  for (const diagnostic& d : t.diagnostics) sink.report(d);
  if (!t.ok) {
    fmt::print(stderr, "timeline: not made: the programs do not check sound ({} error{})\n", sink.errors(),
               sink.errors() == 1 ? "" : "s");
    return 1;
  }
  if (vm.count("output")) {
    const std::string out = vm["output"].as<std::string>();
    if (!write_file(out, timeline_page(t, fmt::format("{} on {}", sources.front().name, m.name)))) {
      print_error(fmt::format("cannot write '{}'", out));
      return 2;
    }
  }
  std::string text;
  if (vm.count("json")) {
    write_timeline_json(
        t, [](std::string_view piece) { std::fwrite(piece.data(), 1, piece.size(), stdout); },
        [&](int channel, const std::function<void(const timed_block&)>& each) {
          for_each_timed_block(t, sources, m, channel, each);
        });
  } else {
    long blocks = 0;
    for (const channel_times& c : t.channels) blocks += c.blocks;
    text = fmt::format("timeline: {} channel{}, {} blocks, machine {}\n", t.channels.size(),
                       t.channels.size() == 1 ? "" : "s", blocks, m.name);
    text += format_timeline_text(t);
    if (vm.count("output")) text += fmt::format("wrote {}\n", vm["output"].as<std::string>());
  }
  std::fwrite(text.data(), 1, text.size(), stdout);
  std::fflush(stdout);
  return 0;
}

}  // namespace twinpost::cli
