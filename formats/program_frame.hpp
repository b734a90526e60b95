#pragma once
// Frames the channels' bodies into the files the control expects: program line, header,
// body, footer and end code per channel, laid out as split files, one merged program with
// the channels appended after their section markers, or `$n` sections.
#include <string>
#include <vector>

#include "machines/machine.hpp"

namespace twinpost {

struct frame_request {
  const machine* machine_def = nullptr;
  layout_kind layout = layout_kind::split;
  std::string name;     ///< safe program name (from PARTNO)
  std::string tmp_dir;  ///< holds body1, body2, ...; the framed files are written here too
};

struct framed_file {
  std::string name;      ///< final file name (no directory)
  std::string tmp_path;  ///< where it was written
};

/// Writes the framed files into the temporary folder; throws config_error on I/O errors.
std::vector<framed_file> frame_programs(const frame_request& r);

}  // namespace twinpost
