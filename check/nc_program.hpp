#pragma once
// Reading NC programs (twinpost's own or anyone else's) into per-channel wait lists, the
// input of the synchronisation checker (check/sync_check.hpp).
//
// Layouts, chosen from the number of files:
// - one file per channel (split): file 1 is channel 1, file 2 channel 2, ...;
// - one file with section markers (merged): machine.program.section_marker with
//   "{channel}" standing for the channel number, e.g. Mazak "G109 L{channel}" or
//   Citizen/Mitsubishi "${channel}". Blocks before the first marker are common and belong
//   to no channel; "$0"-style section 0 is data. Sections may come in any order and a
//   channel's sections may appear more than once: they are joined in file order.
//
// A wait is a word of address machine.waits.address whose code satisfies
// machine.waits.is_wait_code(); with waits.syntax = bang (Citizen/Mitsubishi) it is
// `<marker><partners><address><number>`, `!2L1`, its partners the other channels (`!23L5`,
// `!2!3L5`), kept as written in nc_wait::partner_text. The reader judges syntax and layout only; the rules
// (partner lists, pairing, deadlocks) are the checker's.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "machines/machine.hpp"
#include "nc/nc_words.hpp"
#include "support/diagnostics.hpp"

namespace twinpost {

/// The longest line the reader takes. No control reads a block anywhere near this long: a
/// longer line is not NC text (a binary file, a line of NULs), and reading it whole would
/// hold it all in memory. It is an error, and the rest of its file is not read.
constexpr std::size_t nc_max_line_bytes = 1 << 20;

/// One NC file: its name (used in messages) and its full text, or the path to read it
/// from piece by piece (memory stays flat however long the program is).
struct nc_source {
  std::string name;
  std::string text;
  std::string path = {};  ///< when set, the file is streamed from here and `text` is ignored
  /// When set, the file is streamed from this copy (from its start, each time it is read)
  /// instead of `path`: see check/nc_input.hpp, for inputs that can be read only once.
  std::shared_ptr<std::FILE> copy = {};
};

/// A place in an NC file.
struct nc_place {
  std::string file;
  int line = 0;             ///< 1-based; 0 = no line (e.g. a channel without a program)
  int column = 0;           ///< 1-based; 0 = no column
  std::string source_line;  ///< the physical line, without its line ending
};

/// One wait as written in a channel's program (or an M-code that looks like one).
struct nc_wait {
  int channel = 0;                 ///< 1-based channel number
  int code = 0;                    ///< the wait code, e.g. 100 for M100
  bool has_partner_list = false;   ///< the block carries a partner list (P word)
  std::string partner_text;        ///< the partner list's value as written ("12")
  bool partners_readable = false;  ///< partner_text could be decoded
  std::vector<int> partners;       ///< decoded channels as written (path digits or mask bits)
  int partner_column = 0;          ///< column of the P word
  nc_place where;                  ///< the wait's M-word
};

/// The waits of one channel's program, in program order.
struct nc_channel_program {
  int channel = 0;                  ///< 1-based channel number
  std::string file;                 ///< the file the program was read from
  std::vector<nc_wait> waits;       ///< codes that are waits of the machine
  std::vector<nc_wait> near_waits;  ///< other codes that look like waits (the checker judges)
  nc_place end;                     ///< the end code (M30, M02, M99) or the last block
};

/// All channels' programs: channel n at index n-1, one entry per machine channel.
struct nc_programs {
  std::vector<nc_channel_program> channels;
};

/// How to read. With `on_wait` set, each wait is handed to it as it is read and not kept in
/// the programs (their `waits` stay empty): a check of a long program then holds only what
/// it simulates.
struct nc_read_options {
  std::function<void(const nc_wait&)> on_wait;
  /// When set, every block of a channel's program (a line with words, in its section, up to
  /// and including the end code) is handed to it, in program order and before the block's
  /// wait goes to `on_wait`: the input of the analyses that need more than the waits (cycle
  /// time, shared spindles, the CL-line map). The block comes split, once, for all of them.
  std::function<void(const nc_block&)> on_block;
  /// When set, every line of a channel's program that has no words but a macro variable
  /// (`#601=#601+1`, `IF [#500 EQ #0] THEN #3000=1`): not a block of on_block (it moves
  /// nothing, and the timer and the spindle rules have nothing to read in it), but the control
  /// emulator's reserved variables are written in such lines. Handed with no words.
  std::function<void(const nc_block&)> on_macro;
  /// When set, called with each block just before on_block or on_macro is: the resource
  /// check's reading (analysis/shared_resources) applies its spindle and modal states to a
  /// block between the two, so a consumer that owes something to the blocks before this one
  /// (post's comparison with the CL: the records written before it) settles it here, with the
  /// states as the blocks before left them, and reads the block itself in on_block.
  std::function<void(const nc_block&)> before_block;
};

/// Reads `files` as the programs of machine `m`; layout and syntax problems go to `sink`.
nc_programs read_nc_programs(const std::vector<nc_source>& files, const machine& m, diagnostic_sink& sink,
                             const nc_read_options& options = {});

/// The reader of read_nc_programs for programs that are handed in piece by piece as they are
/// produced (post's self-check reads each channel's program while its writer writes it):
/// one program per channel (the split layout), each fed in order; the channels' pieces may
/// come in any interleaving, and every consumer of `options` gets each channel's blocks and
/// waits in that channel's order. What it reads is what read_nc_programs reads from the same
/// bytes.
class nc_stream_reader {
 public:
  nc_stream_reader(const machine& m, diagnostic_sink& sink, const nc_read_options& options);
  ~nc_stream_reader();
  nc_stream_reader(const nc_stream_reader&) = delete;
  nc_stream_reader& operator=(const nc_stream_reader&) = delete;
  /// Starts the program of `channel` (1-based), named `name` in messages and places.
  void open(int channel, std::string name);
  /// The next bytes of `channel`'s program; `chunk.data()[chunk.size()]` must be a NUL.
  void feed(int channel, std::string_view chunk);
  /// Ends every program opened and returns them all, as read_nc_programs would.
  nc_programs finish();

 private:
  struct impl;
  std::unique_ptr<impl> p_;
};

}  // namespace twinpost
