#pragma once
// Test support for tests that write files and read them back.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <stdlib.h>  // mkdtemp
#include <string>
#include <unistd.h>
#include <vector>

namespace twinpost::test {

/// The whole file, or "(missing)" when it cannot be opened.
inline std::string read_file(const std::string& path) {
  std::string s;
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) return "(missing)";
  char buf[4096];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) s.append(buf, n);
  std::fclose(f);
  return s;
}

/// Writes `text` to `path`; false when it cannot.
inline bool write_file(const std::string& path, const std::string& text) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return false;
  const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  return std::fclose(f) == 0 && ok;
}

/// A fresh, empty folder under the system's temp folder, made by mkdtemp: no other call,
/// process or test run (ctest -j, two builds at once) ever gets the same one. `tag` names it
/// for a person looking at the temp folder: "twinpost-TAG-XXXXXX".
inline std::string fresh_temp_dir(const std::string& tag) {
  std::string dir = (std::filesystem::temp_directory_path() / ("twinpost-" + tag + "-XXXXXX")).string();
  if (::mkdtemp(dir.data()) == nullptr)
    throw std::runtime_error("mkdtemp " + dir + ": cannot make a temp folder");
  return dir;
}

/// Removes a folder and what is in it when it goes out of scope (a test's fresh_temp_dir).
struct removed_at_end {
  std::string dir;
  ~removed_at_end() {
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
  }
};

/// Every file of a folder: name -> contents (empty when there is no folder).
inline std::map<std::string, std::string> read_dir_files(const std::string& dir) {
  std::map<std::string, std::string> files;
  std::error_code ec;
  if (!std::filesystem::exists(dir, ec)) return files;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    files[e.path().filename().string()] = read_file(e.path().string());
  return files;
}

/// The names in a folder, sorted, joined by spaces ("(missing)" when there is no folder).
inline std::string list_dir(const std::string& dir) {
  std::error_code ec;
  if (!std::filesystem::exists(dir, ec)) return "(missing)";
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "" : " ") + n;
  return s;
}

}  // namespace twinpost::test
