#include "analysis/length_offset.hpp"

#include <fmt/format.h>

#include <string>

namespace twinpost {

namespace {

struct channel_state {
  bool on = false;    // a length offset in force
  bool home = false;  // no axis moved since the last reference return
  int on_line = 0;    // the block that turned it on
  std::string on_code;
};

constexpr std::uint32_t axes = nc_letter('X') | nc_letter('Y') | nc_letter('Z') | nc_letter('U') |
                               nc_letter('V') | nc_letter('W') | nc_letter('A') | nc_letter('B') |
                               nc_letter('C');

}  // namespace

struct length_offset_rule::impl {
  std::vector<channel_state> channels;
  std::vector<diagnostic> found;

  // The change in the number of channels with an offset in force.
  int block(const nc_block& b) {
    if (b.channel < 1 || static_cast<std::size_t>(b.channel) > channels.size()) return 0;
    channel_state& c = channels[static_cast<std::size_t>(b.channel - 1)];
    const bool was_on = c.on;
    // With no offset in force only a block that turns one on matters, and it names its register
    // (G43 H1, G43.4 H1, the Integrex's G43 P1 H#3020): a block without H is passed over.
    if (!c.on && !b.may_have(nc_letter('H'))) return 0;
    if (!b.may_have(nc_letter('G'))) {
      // Without a G word: a move of the modal motion if it has an axis word. Only asked right
      // after a home return with an offset in force: once per home, not per block.
      if (c.on && c.home && (b.letters() & axes) != 0) c.home = false;
      return 0;
    }
    bool homes = false, machine_coordinates = false, moves = false, moves_z = false, cancel = false;
    int cancel_column = 0;
    const char* on_code = nullptr;
    for (const nc_word& w : b.words()) {
      if (w.address == 'G' && w.numeric) {
        const double v = w.number;
        if (v == 28 || v == 30) homes = true;
        if (v == 53) machine_coordinates = true;
        if (v == 43) on_code = "G43";
        if (v == 44) on_code = "G44";
        if (v == 43.4) on_code = "G43.4";
        if (v == 43.5) on_code = "G43.5";
        if (v == 49) {
          cancel = true;
          cancel_column = w.column;
        }
      } else if ((nc_letter(w.address) & axes) != 0) {
        moves = true;
        if (w.address == 'Z' || w.address == 'W') moves_z = true;
      }
    }
    // A reference return, or Z (a lathe's W) moved in machine coordinates (G53 Z0.).
    const bool at_home = homes || (machine_coordinates && moves_z);
    if (cancel) {
      if (c.on && !c.home && !at_home)
        found.push_back(
            {severity::warning, b.file, b.line, cancel_column,
             fmt::format("channel {}: G49 cancels the length offset ({} at line {}) away from the "
                         "home position: a control that cancels at once moves Z towards the part "
                         "by the tool's length; cancel it after the reference return (G28/G53 Z)",
                         b.channel, c.on_code, c.on_line),
             std::string(b.text)});
      c.on = false;
    }
    if (on_code) {
      if (!c.on) c.home = false;  // not followed while off: at home only if this block homes
      c.on = true;
      c.on_line = b.line;
      c.on_code = on_code;
    }
    if (at_home)
      c.home = true;
    else if (moves)
      c.home = false;
    return static_cast<int>(c.on) - static_cast<int>(was_on);
  }
};

length_offset_rule::length_offset_rule(std::size_t channels) : p_(std::make_unique<impl>()) {
  p_->channels.resize(channels);
}
length_offset_rule::~length_offset_rule() = default;

void length_offset_rule::read(const nc_block& b) { on_ += p_->block(b); }

std::vector<diagnostic> length_offset_rule::finish() { return std::move(p_->found); }

}  // namespace twinpost
