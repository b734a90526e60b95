// twinpost: the thin command-line tool over the library.
#include <cstdio>
#include <exception>
#include <string>
#include <string_view>

#include "cli/cli_util.hpp"
#include "cli/command_table.hpp"
#include "cli/version.hpp"
#include "machines/machine.hpp"
#include "support/errors.hpp"

int main(int argc, char** argv) {
  const std::string usage = twinpost::cli::usage_text();
  if (argc < 2) {
    std::fputs(usage.c_str(), stderr);
    return 2;
  }
  std::string_view command = argv[1];
  twinpost::cli::args rest(argv + 2, argv + argc);
  try {
    for (const twinpost::cli::command_entry& c : twinpost::cli::command_table())
      if (command == c.name) return c.run(rest);
    if (command == "--man") {  // the build writes twinpost.1 with this
      std::fputs(twinpost::cli::man_page().c_str(), stdout);
      return 0;
    }
    if (command == "--version" || command == "-V") {
      std::printf("twinpost %s (commit %s)\n", twinpost::cli::version(), twinpost::cli::commit());
      return 0;
    }
    if (command == "--help" || command == "-h" || command == "help") {
      std::fputs(usage.c_str(), stdout);
      return 0;
    }
    std::fprintf(stderr, "twinpost: unknown command '%s'\n\n%s", argv[1], usage.c_str());
    return 2;
  } catch (const twinpost::config_error& e) {
    twinpost::cli::print_error(e);
    return 2;
  } catch (const std::exception& e) {
    twinpost::cli::print_error(e.what());
    return 2;
  }
}
