#include "post/output_commit.hpp"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fmt/format.h>
#include <mutex>
#include <set>
#include <sys/stat.h>
#include <unistd.h>

#include "machines/machine.hpp"
#include "post/folder_lock.hpp"
#include "post/temp_registry.hpp"
#include "support/errors.hpp"

namespace fs = std::filesystem;

namespace twinpost {

namespace {

constexpr std::string_view stage_prefix = ".twinpost-";
constexpr int make_attempts = 8;  // another run may remove a folder we are about to use

std::atomic<unsigned> stage_counter{0};  // several posts may run in one process

// The stages of this process's posts in progress: a stage with this process's pid that is
// not among them was left by a dead process that had the same pid.
std::mutex live_mutex;
std::set<std::string> live_stages;

bool is_live_stage(const std::string& path) {
  std::lock_guard<std::mutex> hold(live_mutex);
  return live_stages.count(path) > 0;
}

void set_live(const std::string& path, bool live) {
  std::lock_guard<std::mutex> hold(live_mutex);
  if (live)
    live_stages.insert(path);
  else
    live_stages.erase(path);
}

std::string join(const std::string& dir, const std::string& name) { return (fs::path(dir) / name).string(); }

[[noreturn]] void fail(const std::string& what, const std::string& path, int err) {
  throw config_error(fmt::format("{} '{}': {}", what, path, std::strerror(err)));
}

// Makes every missing folder of `dir`, outermost first, adding those it made to `made`.
// False when a folder vanished under it (another run removed it: try again).
bool make_folders(const std::string& dir, std::vector<std::string>& made) {
  fs::path prefix;
  for (const fs::path& part : fs::path(dir)) {
    prefix /= part;
    const std::string p = prefix.string();
    if (::mkdir(p.c_str(), 0777) == 0) {
      if (std::find(made.begin(), made.end(), p) == made.end()) made.push_back(p);
      continue;
    }
    const int err = errno;
    if (err == ENOENT) return false;
    struct stat st {};
    if (::stat(p.c_str(), &st) == 0 && S_ISDIR(st.st_mode)) continue;
    fail("cannot create", p, err == EEXIST ? ENOTDIR : err);
  }
  return true;
}

// The pid in a stage's name (".twinpost-<pid>" or ".twinpost-<pid>-<n>"), or 0.
pid_t stage_pid(std::string_view name) {
  if (!name.starts_with(stage_prefix)) return 0;
  name.remove_prefix(stage_prefix.size());
  const std::size_t digits = std::min(name.find_first_not_of("0123456789"), name.size());
  if (digits == 0 || digits > 9 || (digits < name.size() && name[digits] != '-')) return 0;
  long pid = 0;
  std::from_chars(name.data(), name.data() + digits, pid);  // at most 9 digits: it fits
  return static_cast<pid_t>(pid);
}

// Stages of runs that died (SIGKILL, power loss) are removed; the caller holds the lock, so
// no live run is making its stage meanwhile, and a live run's pid answers kill(pid, 0).
void remove_dead_stages(const std::string& out) {
  std::error_code ec;
  for (fs::directory_iterator it(out, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    const pid_t pid = stage_pid(name);
    if (pid <= 0) continue;
    const bool dead =
        pid == ::getpid() ? !is_live_stage(it->path().string()) : ::kill(pid, 0) != 0 && errno == ESRCH;
    std::error_code rm;
    if (dead) fs::remove_all(it->path(), rm);
  }
}

}  // namespace

output_stage::output_stage(std::string out_dir) : out_(std::move(out_dir)) {
  signals_held held;
  try {
    make_stage();
  } catch (...) {
    // No destructor runs for a constructor that throws: the folders made so far go here.
    std::sort(made_.begin(), made_.end(),
              [](const std::string& a, const std::string& b) { return a.size() < b.size(); });
    for (auto it = made_.rbegin(); it != made_.rend(); ++it) ::rmdir(it->c_str());
    throw;
  }
}

void output_stage::make_stage() {
  for (int attempt = 0; attempt < make_attempts; ++attempt) {
    if (!make_folders(out_, made_)) continue;
    folder_lock lock(out_);
    if (!lock.ok()) {
      if (lock.error() == ENOENT) continue;
      fail("cannot open", out_, lock.error());
    }
    if (!lock.still_named(out_)) continue;
    remove_dead_stages(out_);
    stage_ = join(out_, fmt::format("{}{}-{}", stage_prefix, ::getpid(), stage_counter++));
    if (::mkdir(stage_.c_str(), 0700) != 0) {
      if (errno == ENOENT) continue;  // removed by an interrupted run, which takes no lock
      fail("cannot write in", out_, errno);
    }
    std::sort(made_.begin(), made_.end(),
              [](const std::string& a, const std::string& b) { return a.size() < b.size(); });
    set_live(stage_, true);
    slot_ = register_temp_dirs(stage_, made_);
    return;
  }
  throw config_error(fmt::format("cannot create '{}': it is removed as often as it is made", out_));
}

output_stage::~output_stage() {
  signals_held held;
  std::error_code ec;
  if (!committed_) {
    folder_lock lock(out_);  // a run staging here waits; its stage keeps the folder non-empty
    fs::remove_all(stage_, ec);
    for (auto it = made_.rbegin(); it != made_.rend(); ++it) ::rmdir(it->c_str());  // only if empty
  }
  unregister_temp_dirs(slot_);
  set_live(stage_, false);
}

std::vector<std::string> output_stage::commit(const std::vector<staged_file>& files,
                                              const std::string& keep) {
  signals_held held;
  folder_lock lock(out_);
  if (!lock.ok()) fail("cannot open", out_, lock.error());
  // Everything that can be known before the first rename is checked before it.
  struct stat kept {};
  const bool keeping = !keep.empty() && ::stat(keep.c_str(), &kept) == 0;
  for (const staged_file& f : files) {
    const std::string target = join(out_, f.name);
    struct stat st {};
    if (keeping && ::stat(target.c_str(), &st) == 0 && st.st_dev == kept.st_dev && st.st_ino == kept.st_ino)
      throw config_error(fmt::format(
          "cannot replace '{}': it is the job being posted (give another output folder)", target));
    if (::lstat(target.c_str(), &st) != 0) continue;
    if (S_ISDIR(st.st_mode)) throw config_error(fmt::format("cannot replace '{}': it is a folder", target));
    if (!S_ISREG(st.st_mode) && !S_ISLNK(st.st_mode))
      throw config_error(fmt::format("cannot replace '{}': it is not a regular file", target));
  }
  if (::access(out_.c_str(), W_OK | X_OK) != 0) fail("cannot write in", out_, errno);
  detail::replace_all(out_, stage_, files);
  committed_ = true;
  std::error_code ec;
  fs::remove_all(stage_, ec);  // the new files have left it; the backups of the old go
  std::vector<std::string> written;
  for (const staged_file& f : files) written.push_back(join(out_, f.name));
  return written;
}

namespace detail {

void replace_all(const std::string& out_dir, const std::string& stage_dir,
                 const std::vector<staged_file>& files) {
  struct step {
    std::string target, backup;
    bool had_old = false, placed = false;
  };
  std::vector<step> done;
  auto undo_and_fail = [&](const std::string& what, const std::string& path, int err) {
    std::string lost;
    for (auto it = done.rbegin(); it != done.rend(); ++it) {
      bool ok = true;
      if (it->had_old)
        ok = ::rename(it->backup.c_str(), it->target.c_str()) == 0;
      else if (it->placed)
        ok = ::unlink(it->target.c_str()) == 0;
      if (!ok) lost += fmt::format(" '{}'", it->target);
    }
    std::string msg = fmt::format("{} '{}': {}", what, path, std::strerror(err));
    if (!lost.empty()) msg += "; could not put back:" + lost;
    throw config_error(msg);
  };
  for (std::size_t i = 0; i < files.size(); ++i) {
    step s;
    s.target = join(out_dir, files[i].name);
    s.backup = join(stage_dir, fmt::format("old-{}", i));
    struct stat st {};
    if (::lstat(s.target.c_str(), &st) == 0) {
      if (S_ISDIR(st.st_mode)) undo_and_fail("cannot replace", s.target, EISDIR);
      // A hard link keeps the old file in place until the new one replaces it atomically;
      // where links are refused (some file systems) the old file moves aside instead.
      if (::link(s.target.c_str(), s.backup.c_str()) != 0 &&
          ::rename(s.target.c_str(), s.backup.c_str()) != 0)
        undo_and_fail("cannot replace", s.target, errno);
      s.had_old = true;
    }
    done.push_back(s);
    if (::rename(files[i].tmp_path.c_str(), s.target.c_str()) != 0)
      undo_and_fail("cannot write", s.target, errno);
    done.back().placed = true;
  }
}

}  // namespace detail

}  // namespace twinpost
