// twinpost parse: print the CL event stream.
#include <boost/program_options.hpp>
#include <cstdio>
#include <fmt/format.h>

#include "cli/cli_util.hpp"
#include "cli/command_table.hpp"
#include "cli/commands.hpp"
#include "parser/cl_reader.hpp"
#include "parser/dialect.hpp"
#include "parser/event_text.hpp"
#include "parser/record_policy.hpp"

namespace twinpost::cli {

namespace po = boost::program_options;

int run_parse(const args& a) {
  po::options_description opts(command_usage("parse"));
  static const std::string dialects =
      names_joined(
          dialect_names, [](const dialect_name_entry& d) { return d.name; }, "|", "|") +
      " (default: detect)";
  opts.add_options()("help,h", "show this help")("json", "one JSON object per event (JSON Lines)")(
      "dialect", po::value<std::string>(), dialects.c_str())(
      "records", "print the record policy (docs/records.md) instead of reading a file")(
      "file", po::value<std::string>(), "CL file");
  po::positional_options_description pos;
  pos.add("file", 1);
  po::variables_map vm;
  if (const std::optional<int> done = parse_command(a, opts, pos, vm, "parse", to_string(opts))) return *done;
  if (vm.count("records")) {
    if (vm.count("file") || vm.count("json") || vm.count("dialect")) {
      fmt::print(stderr, "twinpost parse: --records takes no file and no other option\n");
      return 2;
    }
    fmt::print("{}", record_policy_markdown());
    return 0;
  }
  if (!vm.count("file")) {
    fmt::print(stderr, "twinpost parse: missing CL file\n");
    return 2;
  }
  std::string path = vm["file"].as<std::string>();
  cl_reader_options ro;
  ro.file_name = path;
  if (vm.count("dialect")) {
    auto d = dialect_from_name(vm["dialect"].as<std::string>());
    if (!d) {
      fmt::print(stderr, "twinpost parse: unknown dialect '{}'\n", vm["dialect"].as<std::string>());
      return 2;
    }
    ro.forced = d;
  }
  open_file in(path);
  if (!in) {
    print_error(fmt::format("cannot read '{}'", path));
    return 2;
  }
  bool json = vm.count("json") > 0;
  printing_sink sink;
  file_source src(in.get());
  cl_reader reader(src, ro, sink);
  event e;
  std::string line;
  while (reader.next(e)) {
    line = json ? event_to_json(e) : event_to_text(e);
    line += '\n';
    std::fwrite(line.data(), 1, line.size(), stdout);
  }
  std::fflush(stdout);
  return sink.errors() > 0 ? 1 : 0;
}

}  // namespace twinpost::cli
