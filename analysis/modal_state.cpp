#include "analysis/modal_state.hpp"

namespace twinpost {

modal_states::modal_states(const machine& m) : units_(units_of(m)) {
  channels_.reserve(m.channels.size());
  for (const channel_def& ch : m.channels) {
    channels_.emplace_back(m, ch);
    channels_.back().modes.inch = units_.inch;
  }
}

void modal_states::apply(slot& s, const std::vector<nc_word>& words) const {
  channel_modes& md = s.modes;
  block_g_codes& now = md.now;
  const bool system_a = s.codes.system() == gcode_system::a;
  for (const nc_word& w : words) {
    if (w.address != 'G' || !w.numeric) continue;
    const double g = w.number;
    now.any = true;
    switch (s.codes.role(g)) {
      case axis_words::motion:
        md.motion = static_cast<int>(g);
        md.hole_cycle = md.turning_cycle = false;
        now.motion = true;
        break;
      case axis_words::hole_cycle:
        md.hole_cycle = true;  // (group 10 on a Fanuc lathe: the single cycle of group 01 stays)
        now.cycle = true;
        break;
      case axis_words::turning_cycle:
        // To its end point and back to its start, block by block until G0-G3; a code of group
        // 01, it ends a drilling cycle as G0-G3 do.
        md.turning_cycle = true;
        md.hole_cycle = false;
        now.cycle = true;
        break;
      case axis_words::repetitive_cycle: now.once = true; break;
      case axis_words::feed_move:
        // Threading (G32, G33, G34, the machine's sync feed): a code of group 01 as G1 is, modal
        // (the next block's Z alone cuts on along the thread).
        md.motion = 32;
        md.hole_cycle = md.turning_cycle = false;
        now.feed_move = true;
        break;
      case axis_words::reference: now.reference = true; break;
      case axis_words::machine: now.machine = true; break;
      case axis_words::none:
        now.no_move = true;
        if (g == 92 || g == 50) now.coordinate_setting = true;
        break;
      case axis_words::modal: break;
    }
    if (g == 80) md.hole_cycle = false;  // (a lathe's single cycle ends at a motion code)
    if ((g >= 54 && g <= 59 && g == static_cast<int>(g)) || g == 54.1) now.work_offset = true;
    if (g == 10 || g == 65 || g == 66 || g == 66.1) now.data = true;
    if (const std::optional<bool> inch = units_.selected_by(g)) {
      md.inch = *inch;
      now.units = true;
    }
    if (g == 12.1 || g == 112) md.polar = now.polar = true;
    if (g == 13.1 || g == 113) md.polar = false, now.polar = true;
    if (g == 17 || g == 18 || g == 19) md.plane = static_cast<int>(g);
    // System A has neither: its G90 is the turning cycle, its increments U and W, and a G91 an
    // alarm. Read as B and C read it, the words after it are increments: the comparison with
    // the CL then finds them off the CL's points, where a G91 taken for nothing would pass a
    // program the control refuses.
    if (g == 91) md.incremental = true;
    if (g == 90 && !system_a) md.incremental = false;
    if (const feed_kind f = s.codes.feed_mode(g); f != feed_kind::none)
      md.feed = f;
    else if (g == 98 || g == 99)
      md.return_to_r = g == 99;
  }
}

}  // namespace twinpost
