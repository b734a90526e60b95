#include "cli/machine_dirs.hpp"

#include <cstdlib>
#include <filesystem>

namespace twinpost::cli {

namespace fs = std::filesystem;

namespace {

// The XDG base directory rule: $XDG_CONFIG_HOME when set to an absolute path, else ~/.config.
std::string user_config_dir() {
  const char* xdg = std::getenv("XDG_CONFIG_HOME");
  if (xdg && xdg[0] == '/') return xdg;
  const char* home = std::getenv("HOME");
  if (home && home[0] == '/') return (fs::path(home) / ".config").string();
  return {};
}

// <prefix>/share/twinpost/machines for a binary installed as <prefix>/bin/twinpost.
std::string installed_share_dir() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec) return {};
  return (exe.parent_path().parent_path() / "share" / "twinpost" / "machines").string();
}

}  // namespace

std::vector<std::string> machine_dirs() {
  std::vector<std::string> dirs;
  if (std::string user = user_config_dir(); !user.empty())
    dirs.push_back((fs::path(user) / "twinpost" / "machines").string());
  dirs.push_back("/etc/twinpost/machines");
  if (std::string share = installed_share_dir(); !share.empty()) dirs.push_back(share);
  return dirs;
}

located_machine locate_machine(const std::string& name_or_path) {
  return find_machine(name_or_path, machine_dirs());
}

}  // namespace twinpost::cli
