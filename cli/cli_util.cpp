#include "cli/cli_util.hpp"

#include <fmt/format.h>
#include <sstream>

namespace twinpost::cli {

namespace po = boost::program_options;

std::optional<int> parse_command(const args& a, const po::options_description& opts,
                                 const po::positional_options_description& pos, po::variables_map& vm,
                                 const char* command, const std::string& help) {
  try {
    po::store(po::command_line_parser(a).options(opts).positional(pos).run(), vm);
    po::notify(vm);
  } catch (const po::error& e) {
    fmt::print(stderr, "twinpost {}: {}\n", command, e.what());
    return 2;
  }
  if (vm.count("help")) {
    fmt::print("{}", help);
    return 0;
  }
  return std::nullopt;
}

void print_error(std::string_view message) { fmt::print(stderr, "twinpost: error: {}\n", message); }

void print_error(const config_error& e) {
  if (e.located())
    fmt::print(stderr, "{}\n", e.what());
  else
    print_error(e.what());
}

std::string to_string(const po::options_description& opts) {
  std::ostringstream s;
  s << opts;
  return s.str();
}

open_file::open_file(const std::string& path, const char* mode) : f_(std::fopen(path.c_str(), mode)) {}
open_file::~open_file() {
  if (f_) std::fclose(f_);
}

void printing_sink::report(diagnostic d) {
  counts_.add(d);
  std::string text = d.file.empty() ? "twinpost: " + format_diagnostic(d) : format_diagnostic(d);
  std::fwrite(text.data(), 1, text.size(), stderr);
}

}  // namespace twinpost::cli
