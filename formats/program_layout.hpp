#pragma once
// Frames the channels' bodies into the files the control expects: program line, header,
// body, footer and end code per channel, laid out as split files, one merged program with
// the channels appended after their section markers, or `$n` sections.
//
// Posting streams: a channel whose blocks open a program file (every channel of a split
// layout, the first channel of a merged one) writes them straight into that file, between
// the head and tail given here. The other channels of a merged program spill their
// sections (marker, header, blocks, footer) to a body file on disk, and finish_frames
// appends them after the first one's. Header and footer blocks are numbered in the count
// of the channel's blocks (formats/sequence_numbers).
#include <functional>
#include <string>
#include <vector>

#include "formats/sequence_numbers.hpp"
#include "machines/machine.hpp"
#include "support/errors.hpp"

namespace twinpost {

struct frame_request {
  const machine* machine_def = nullptr;
  layout_kind layout = layout_kind::split;
  std::string name;     ///< safe program name (from PARTNO), as far as it is known
  std::string tmp_dir;  ///< the program files and spilled bodies are written here
  std::string out_dir;  ///< the folder the files go to (named in messages)
  /// What becomes of each header and footer block of a channel's section (the machine's
  /// script's on_block, docs/scripting.md): the blocks written in its place, in order (none:
  /// dropped). Not given: each as it is. Not for the program line, the section marker, a
  /// comment line or the end code: they frame the program.
  /// `index`: the block's place in the machine file's header or footer list.
  std::function<std::vector<std::string>(const channel_def&, const std::string& block, bool header,
                                         std::size_t index)>
      edit_block;
};

/// Where a channel's blocks go.
struct channel_target {
  std::string path;  ///< the program file's temporary path, or a body file
};

struct framed_file {
  std::string name;      ///< final file name (no directory)
  std::string tmp_path;  ///< where it was written
  int channel = 0;       ///< the channel that opens the file
  /// The file is not byte for byte what its channel's writer wrote: its head was written
  /// again under the right name, or other channels' sections were appended (merged).
  bool rewritten = false;
};

channel_target frame_target(const frame_request& r, const channel_def& ch);

/// The name (no folder) of the program file that channel `ch`'s blocks end up in.
std::string frame_file_name(const frame_request& r, const channel_def& ch);

/// The lines before a channel's blocks: '%' and the program line when the channel opens
/// its file, its section marker (merged layouts) and the channel header, the header blocks
/// numbered from `seq`; each line ends in '\n'.
std::string frame_head(const frame_request& r, const channel_def& ch, sequence_numbers& seq);

/// The lines after a channel's blocks: footer and end code (numbered on from `seq`), and the
/// closing '%' when the channel ends its file. A footer block equal to one of `in_force` (the
/// channel's last M9 or M5, still in force: channel_writer::footer_in_force) is left out.
std::string frame_tail(const frame_request& r, const channel_def& ch, sequence_numbers& seq,
                       const std::vector<std::string>& in_force = {});

/// Completes the program files once every channel has finished: appends the spilled
/// channels' sections to a merged program, and gives a file or section a new head when the
/// name it was begun under (`heads`: per channel, the head written) is not `r.name` (a
/// PARTNO after the first block). Throws config_error on I/O errors.
std::vector<framed_file> finish_frames(const frame_request& r, const std::vector<std::string>& heads);

}  // namespace twinpost
