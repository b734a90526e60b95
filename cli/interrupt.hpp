#pragma once
// The command-line tool's answer to SIGINT, SIGTERM and SIGHUP during a post: remove what
// the run staged (the library's registry of temporary folders), then die of the signal so
// that the caller sees the conventional status (128 + signal number in a shell).
// Header-only so that the tests install exactly this handler in a child process.
#include <csignal>

#include "post/temp_registry.hpp"

namespace twinpost::cli {

/// The handler: async-signal-safe (the registry's removal uses system calls only).
inline void on_interrupt(int sig) {
  remove_registered_temp_dirs();
  ::signal(sig, SIG_DFL);
  ::raise(sig);  // delivered when the handler returns: the process dies of `sig`
}

/// Installs on_interrupt for SIGINT, SIGTERM and SIGHUP, except where a signal was
/// ignored when the tool started (nohup, background jobs of a non-interactive shell).
inline void install_interrupt_cleanup() {
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction old {};
    if (::sigaction(sig, nullptr, &old) != 0 || old.sa_handler == SIG_IGN) continue;
    struct sigaction sa {};
    sa.sa_handler = &on_interrupt;
    sigemptyset(&sa.sa_mask);
    ::sigaction(sig, &sa, nullptr);
  }
}

}  // namespace twinpost::cli
