#include "fuzz/fuzz_support.hpp"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <unistd.h>

#include "machines/builtin_machines.hpp"
#include "machines/machine_loader.hpp"

namespace twinpost::fuzz {

namespace {

struct scratch {
  std::string path;
  scratch() {
    const char* base = std::getenv("TMPDIR");
    std::string tpl = std::string(base && *base ? base : "/tmp") + "/twinpost-fuzz-XXXXXX";
    if (!::mkdtemp(tpl.data())) {
      std::perror("mkdtemp");
      std::abort();
    }
    path = tpl;
  }
  ~scratch() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
};

}  // namespace

const std::string& scratch_dir() {
  static scratch s;
  return s.path;
}

const std::vector<machine>& builtin_machine_defs() {
  static const std::vector<machine> all = [] {
    std::vector<machine> v;
    for (const builtin_machine_file& f : builtin_machine_files()) v.push_back(load_machine(f.name));
    return v;
  }();
  return all;
}

void require(bool ok, std::string_view what) {
  if (ok) return;
  std::fprintf(stderr, "fuzz property failed: %.*s\n", static_cast<int>(what.size()), what.data());
  std::abort();
}

std::string read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_all(const std::string& path, std::string_view text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  out.close();
  require(static_cast<bool>(out), "writing a scratch file");
}

}  // namespace twinpost::fuzz
