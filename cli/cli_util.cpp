#include "cli/cli_util.hpp"

#include <fmt/format.h>
#include <sstream>

namespace twinpost::cli {

namespace po = boost::program_options;

bool parse_options(const args& a, const po::options_description& opts,
                   const po::positional_options_description& pos, po::variables_map& vm,
                   const char* command) {
  try {
    po::store(po::command_line_parser(a).options(opts).positional(pos).run(), vm);
    po::notify(vm);
    return true;
  } catch (const po::error& e) {
    fmt::print(stderr, "twinpost {}: {}\n", command, e.what());
    return false;
  }
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
  if (d.level == severity::error) ++errors_;
  if (d.level == severity::warning) ++warnings_;
  std::string text = format_diagnostic(d);
  std::fwrite(text.data(), 1, text.size(), stderr);
}

}  // namespace twinpost::cli
