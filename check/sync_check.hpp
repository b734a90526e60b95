#pragma once
// The synchronisation checker: proves that the waits of all channels pair up and that the
// channels, run together, cannot deadlock. The post command runs it on its own output
// before writing; `twinpost check` runs it on any NC programs.
//
// Rules (see docs/checker.md):
// - pairing is by code and by order: the k-th wait of a channel meets the k-th wait of
//   its partners, with the same code and the same partner list; codes may be reused;
// - a channel that reaches a wait stops until every partner reaches its matching wait;
// - with three or more channels on a machine with partner lists, every wait names its
//   partners, including its own channel, and only channels the machine has (PS0161);
// - a machine whose waits take no partner list must get none;
// - an M-code that looks like a wait but is not one of the machine's wait codes is flagged.
// The simulation is linear in the number of waits.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "check/nc_program.hpp"
#include "machines/machine.hpp"
#include "support/diagnostics.hpp"

namespace twinpost {

/// Per channel: how many waits its program has and how many met their partners.
struct channel_sync_summary {
  int channel = 0;
  std::string file;
  int waits = 0;
  int paired = 0;
};

/// The outcome of a check.
struct sync_result {
  bool ok = true;                       ///< no errors
  std::vector<diagnostic> diagnostics;  ///< problems in report order
  std::vector<channel_sync_summary> channels;
  int paired = 0;  ///< waits of all channels that met their partners
  int errors = 0;
  int warnings = 0;
  /// The rendezvous of the simulation in the order it released them, each as the set of
  /// its channels (bit c-1 for channel c): every channel's own waits in program order. The
  /// happens-before order of the channels' blocks follows from it (analysis/shared_resources).
  std::vector<std::uint64_t> rendezvous;
};

/// Checks the waits of `programs` against the rules of machine `m` and simulates the
/// channels together; reports unpaired waits, mismatches and deadlocks.
sync_result check_sync(const nc_programs& programs, const machine& m);

/// Reads `files` as NC programs of machine `m` and checks them: reading problems first. A
/// program of two or more channels in which no wait of the machine is found is an error
/// ("is this the right machine?"): a check that checked nothing never says sound.
/// `also`: its on_block and on_wait are called too, during the first reading (each block and
/// wait once), for the analyses that read the programs with the check (check_resources).
sync_result check_nc_files(const std::vector<nc_source>& files, const machine& m,
                           const nc_read_options& also = {});

/// The first, compact reading of check_nc_files, for a caller that reads the programs
/// itself (post reads its programs while they are written: nc_stream_reader). Read with
/// options(), reading problems into a diagnostic_list; then result().
class compact_sync_check {
 public:
  /// `also`: as for check_nc_files.
  explicit compact_sync_check(const machine& m, const nc_read_options& also = {});
  ~compact_sync_check();
  compact_sync_check(const compact_sync_check&) = delete;
  compact_sync_check& operator=(const compact_sync_check&) = delete;
  /// What to read with: the waits to the check (and to `also`), the blocks to `also`.
  const nc_read_options& options() const;
  /// The check of what was read, when the reading found nothing to say (nothing in `read`,
  /// no code that looks like a wait, every channel at its end): what check_nc_files returns
  /// then. nullopt: the programs need the full check (check_nc_files) for its messages.
  std::optional<sync_result> result(const nc_programs& programs, const diagnostic_list& read);

 private:
  struct impl;
  std::unique_ptr<impl> p_;
};

}  // namespace twinpost
