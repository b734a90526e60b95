// twinpost: the thin command-line tool over the library.
#include <cstdio>
#include <exception>
#include <string>
#include <string_view>

#include "cli/commands.hpp"
#include "machines/machine.hpp"

namespace {

const char* const usage =
    "usage: twinpost <command> [options]\n"
    "\n"
    "commands:\n"
    "  parse FILE [--json] [--dialect D]          print the CL event stream\n"
    "  post JOB --machine M -o DIR [--layout L]   post a CL job to NC programs\n"
    "  check FILE... --machine M [--json]         check wait synchronisation of NC programs\n"
    "  machines                                   list the built-in machines\n"
    "\n"
    "Run 'twinpost <command> --help' for the options of a command.\n";

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fputs(usage, stderr);
    return 2;
  }
  std::string_view command = argv[1];
  twinpost::cli::args rest(argv + 2, argv + argc);
  try {
    if (command == "parse") return twinpost::cli::run_parse(rest);
    if (command == "post") return twinpost::cli::run_post(rest);
    if (command == "check") return twinpost::cli::run_check(rest);
    if (command == "machines") return twinpost::cli::run_machines(rest);
    if (command == "--help" || command == "-h" || command == "help") {
      std::fputs(usage, stdout);
      return 0;
    }
    std::fprintf(stderr, "twinpost: unknown command '%s'\n\n%s", argv[1], usage);
    return 2;
  } catch (const twinpost::config_error& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "twinpost: error: %s\n", e.what());
    return 2;
  }
}
