// twinpost check: proves the waits of NC programs.
#include <boost/program_options.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "analysis/shared_resources.hpp"
#include "check/sync_check.hpp"
#include "check/sync_report.hpp"
#include "cli/cli_util.hpp"
#include "cli/command_table.hpp"
#include "cli/commands.hpp"
#include "cli/machine_dirs.hpp"
#include "support/errors.hpp"

namespace twinpost::cli {

namespace {

std::string check_usage() {
  return "usage: " + command_usage("check") +
         "\n"
         "\n"
         "Checks that the waits of NC programs pair up and cannot deadlock, and that channels\n"
         "that may run at the same time do not command a shared spindle differently. Give one\n"
         "file per channel, in channel order, or one file with the machine's section markers.\n"
         "Exit status: 0 sound, 1 problems found, 2 usage or configuration error.\n"
         "\n";
}

/// True when `path` is a regular file that opens for reading, or a pipe, FIFO or device:
/// those are not opened here, since opening a FIFO to look at it takes its writer's data
/// away. The checker reads each of them exactly once (check/nc_input.hpp) and says so
/// when it cannot.
bool readable(const std::string& path) {
  std::error_code ec;
  const std::filesystem::file_status st = std::filesystem::status(path, ec);
  if (ec || st.type() == std::filesystem::file_type::not_found) return false;
  if (st.type() == std::filesystem::file_type::directory) return false;  // opens, reads nothing
  if (st.type() != std::filesystem::file_type::regular) return true;
  open_file probe(path);
  return static_cast<bool>(probe);
}

}  // namespace

int run_check(const args& a) {
  namespace po = boost::program_options;
  po::options_description opts("options");
  opts.add_options()("help,h", "show this help")("machine,m", po::value<std::string>(),
                                                 "built-in machine name or machine file (required)")(
      "json", "print the report as one JSON object");
  po::options_description all;
  all.add(opts).add_options()("file", po::value<std::vector<std::string>>(), "NC files");
  po::positional_options_description pos;
  pos.add("file", -1);
  po::variables_map vm;
  if (const std::optional<int> done =
          parse_command(a, all, pos, vm, "check", check_usage() + to_string(opts)))
    return *done;
  if (!vm.count("file")) {
    fmt::print(stderr, "twinpost check: missing NC files\n");
    return 2;
  }
  if (!vm.count("machine")) {
    fmt::print(stderr, "twinpost check: missing --machine\n");
    return 2;
  }

  // A bad machine throws config_error, which main turns into its message and exit 2.
  const machine m = locate_machine(vm["machine"].as<std::string>()).def;

  std::vector<nc_source> sources;
  for (const std::string& path : vm["file"].as<std::vector<std::string>>()) {
    // Streamed by the checker: an NC program may be far larger than memory should hold.
    if (!readable(path)) {
      print_error(fmt::format("cannot read '{}'", path));
      return 2;
    }
    sources.push_back({path, {}, path});
  }

  const sync_result r = check_nc_resources(sources, m);
  const std::string report = vm.count("json") ? format_sync_json(r) : format_sync_text(r);
  std::fwrite(report.data(), 1, report.size(), stdout);
  std::fflush(stdout);
  return r.ok ? 0 : 1;
}

}  // namespace twinpost::cli
