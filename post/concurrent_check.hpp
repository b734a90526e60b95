#pragma once
// The self-check on the second core: post's programs read while they are written.
//
// Each channel's writer hands every full buffer of its program's bytes to this class instead
// of writing it (block_writer::relay); a thread of this class reads them with the checker's
// own reader (check/nc_program's nc_stream_reader), feeding the same consumers as the check
// after the fact (the wait check, the shared-spindle rules and the cycle time), and then
// writes them to the file: the post's thread neither copies nor writes its output. It reads
// the bytes that are committed, not the writers' words, so the check stays independent of
// the writer.
//
// The result is taken only when it is exactly what the check after the fact would give:
// each file's bytes are the ones read (no head written again, no merged layout), read under
// the name they are committed as, and the check had nothing to say (its messages are
// ordered by a reading of the files one after the other, which the concurrent one is not).
// Otherwise finish() says so and post checks the files after the fact, as with one core.
//
// The comparison of each channel's program with its CL (analysis/cl_compare) runs here too,
// from the same reading: every block the check reads (split once for all its consumers) goes
// to the channel's comparison, and each CL record the writer noted (note_record) before the
// block that starts where the bytes written before it end; it then stands whether or not the
// check does.
//
// Memory: a few pieces of 64 KB queued; the writer waits when the reader is behind. The
// buffers go round: a piece written is the next empty buffer of a writer. The records noted
// travel with the next piece: at most `records_per_piece` of them wait for one.
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "analysis/cl_compare.hpp"
#include "analysis/cycle_time.hpp"
#include "check/sync_check.hpp"
#include "formats/block_writer.hpp"
#include "machines/machine.hpp"

namespace twinpost {

class concurrent_check {
 public:
  /// Records noted for a channel before its writer should pass its bytes (note_record).
  static constexpr std::size_t records_per_piece = 1024;

  /// Starts the reading thread. `feed`, when given, is fed every block and wait (from that
  /// thread, until finish() returns). `compare[c]`, when not null, compares channel c+1's
  /// program with its CL on that thread, until drain() returns; it must outlive that.
  concurrent_check(const machine& m, timeline_feed* feed, std::vector<cl_comparison*> compare = {});
  /// Stops the thread once every piece handed in is read and written (a post that failed
  /// does not wait for its check, but its files get every byte their writers gave).
  ~concurrent_check();
  concurrent_check(const concurrent_check&) = delete;
  concurrent_check& operator=(const concurrent_check&) = delete;

  /// The writer of `channel`'s program (1-based) hands its bytes to this (block_writer::relay):
  /// the thread reads each piece, then writes it to the writer's file. The first piece opens
  /// the program under `name()` (the name its file is committed as, as far as known then),
  /// asked on the writer's thread. The relay must not be used after this object is gone.
  std::unique_ptr<block_writer::relay> relay_for(int channel, std::function<std::string()> name);

  /// A record of `channel` shown to its comparison after the first `bytes` bytes of its program
  /// (block_writer::bytes_out, between blocks: before the block that starts there; the
  /// writer's thread, in the order of the records; `both`: a HEAD/BOTH copy). True when
  /// records_per_piece of them wait for the next piece: its writer should pass its bytes now.
  bool note_record(int channel, std::uint64_t bytes, const event& e, bool both);
  /// The job's units (UNITS record) for `channel`'s comparison, after `bytes` bytes.
  bool note_units(int channel, std::uint64_t bytes, unit_system u);
  /// The records noted for `channel` go to the thread now, without bytes: after its writer
  /// passed its bytes (block_writer::pass_now), when it has none to pass (nothing written since
  /// its last piece, or nothing yet): so that records_per_piece bounds them however little a
  /// stretch of records writes (review 67 M3).
  void flush_records(int channel);

  /// Waits for the reading to end, and hands each comparison the records noted after its
  /// program's last block. False: a comparison did not see its whole program (the reading or
  /// the comparison failed; `why` says what was thrown). Idempotent.
  bool drain(std::string* why = nullptr);

  /// Waits for the reading to end (drain); the check's result when it may stand for the check of
  /// the committed files named `names` (by channel), read one after the other, with
  /// `rewritten` telling which of them are not what their writer wrote. nullopt: check
  /// those files after the fact (and feed a fresh timeline).
  std::optional<sync_result> finish(const std::vector<std::string>& names,
                                    const std::vector<bool>& rewritten);

 private:
  struct impl;
  struct channel_relay;
  std::unique_ptr<impl> p_;
};

}  // namespace twinpost
