// libFuzzer target: a machine file with user blocks, posted (issue 38, "fuzzing that reaches
// it"). The input's first byte picks a built-in machine that posts the target's job and where
// the blocks go (a CL record's `[[events.record]]`, the tool change's `[events]` blocks, or
// both); the rest is the blocks, one per line (at most 8), written into the machine file's TOML
// as strings. The machine file is loaded from that text as a user's would be, and the job
// posted. Properties:
// - every post keeps fuzz::post_checked's (returns or config_error, positions, no file after
//   a failure, `check` sound, the files it names);
// - a user block the post wrote is read again by the checker's word splitter (check/
//   nc_program, another reader than the gate's): no G code outside the gate's whitelist, no
//   program number, no subprogram call or return, no wait word (the job has one channel's
//   work: a wait there never pairs, and the self-check must have refused it).
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "fuzz/fuzz_support.hpp"
#include "machines/builtin_machines.hpp"
#include "machines/code_overlap.hpp"
#include "machines/machine_loader.hpp"
#include "nc/nc_words.hpp"
#include "support/errors.hpp"

using namespace twinpost;

namespace {

// A drill on the centre line, the user's record between its approach and its cut.
constexpr std::string_view job_text =
    "PARTNO FZ\nTLDATA/DRILL,8,118\nLOADTL/1\nSPINDL/RPM,800,CLW\nFEDRAT/MMPM,100\nRAPID\nGOTO/0,0,2\n"
    "CATCHER\nGOTO/0,0,-10\nRAPID\nGOTO/0,0,5\nFINI\n";

// The gate's G codes (machining/user_block_form.cpp), in tenths.
constexpr int whitelist[] = {0,   10,  20,  30,  40,  90,  100, 170, 180, 190, 200, 210, 280, 300, 400,
                             500, 520, 530, 610, 640, 800, 900, 910, 920, 940, 950, 960, 970, 980, 990};

// `s` as a TOML basic string: quotes, backslashes and every byte outside printable ASCII escaped.
std::string toml_string(std::string_view s) {
  std::string out = "\"";
  for (const char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\')
      out += std::string("\\") + c;
    else if (u < 0x20 || u >= 0x7f)
      out += fmt::format("\\u{:04X}", u);
    else
      out += c;
  }
  return out + "\"";
}

std::string toml_array(const std::vector<std::string>& blocks) {
  std::string out = "[";
  for (std::size_t i = 0; i < blocks.size(); ++i) out += (i ? ", " : "") + toml_string(blocks[i]);
  return out + "]";
}

struct target_machine {
  std::string_view name, toml;
};

// The built-in machines the job posts on with a harmless user block (not the check-only ones).
const std::vector<target_machine>& machines() {
  static const std::vector<target_machine> all = [] {
    std::vector<target_machine> v;
    const std::string dir = fuzz::scratch_dir();
    fuzz::write_all(dir + "/job.cls", job_text);
    for (const builtin_machine_file& f : builtin_machine_files()) {
      try {
        const machine m = parse_machine(
            std::string(f.toml) + "\n[[events.record]]\nmajor = \"CATCHER\"\nblocks = [\"M8\"]\n", "fz.toml");
        if (fuzz::post_checked(dir + "/job.cls", dir + "/probe", m, layout_kind::split, false).ok)
          v.push_back({f.name, f.toml});
      } catch (const config_error&) {
      }
    }
    fuzz::require(!v.empty(), "no built-in machine posts the events target's job");
    return v;
  }();
  return all;
}

// The checker's reading of a block the gate let through.
void read_again(std::string_view block, const machine& m) {
  for (const nc_word& w : split_nc_words(block)) {
    if (!w.numeric) continue;
    const double v = w.number;
    if (w.address == 'G') {
      const int tenths = static_cast<int>(std::lround(v * 10));
      fuzz::require(
          std::abs(v * 10 - tenths) < 1e-6 &&
              std::find(std::begin(whitelist), std::end(whitelist), tenths) != std::end(whitelist),
          "a user block the post wrote has a G code outside the gate's whitelist: " + std::string(block));
    }
    fuzz::require(w.address != 'O',
                  "a user block the post wrote has a program number: " + std::string(block));
    if (w.address == 'M')
      fuzz::require(v != 98 && v != 99 && v != 198,
                    "a user block the post wrote calls a subprogram: " + std::string(block));
    fuzz::require(
        !(v >= 0 && v == std::floor(v) && is_wait_word(m.waits, w.address, static_cast<long long>(v))),
        "a user block the post wrote has a wait word in a one-channel job: " + std::string(block));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::vector<target_machine>& all = machines();
  const target_machine& pick = all[data[0] % all.size()];
  const int where = (data[0] / all.size()) % 3;  // 0: the record, 1: the tool change, 2: both
  std::vector<std::string> blocks;
  const std::string_view text(reinterpret_cast<const char*>(data) + 1, size - 1);
  for (std::size_t at = 0; at <= text.size() && blocks.size() < 8;) {
    std::size_t end = text.find('\n', at);
    if (end == std::string_view::npos) end = text.size();
    blocks.emplace_back(text.substr(at, std::min<std::size_t>(end - at, 256)));
    at = end + 1;
  }
  std::string toml(pick.toml);
  toml += "\n[events]\n";
  if (where != 0) toml += "tool_change.after = " + toml_array(blocks) + "\n";
  toml +=
      "\n[[events.record]]\nmajor = \"CATCHER\"\nblocks = " + (where != 1 ? toml_array(blocks) : "[\"M8\"]") +
      "\n";
  machine m;
  try {
    m = parse_machine(toml, "fz.toml");
  } catch (const config_error&) {
    return 0;  // refused at load: the tool's exit 2
  }
  const std::string dir = fuzz::scratch_dir();
  fuzz::write_all(dir + "/job.cls", job_text);
  const fuzz::post_outcome r =
      fuzz::post_checked(dir + "/job.cls", dir + "/out", m, layout_kind::split, false);
  if (!r.ok) return 0;
  for (const std::string& program : r.contents)
    for (const std::string& b : blocks)
      if (program.find("\n" + b + "\n") != std::string::npos) read_again(b, m);
  return 0;
}
