#include "analysis/interference.hpp"

#include "analysis/nc_codes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fmt/format.h>
#include <memory>
#include <numbers>
#include <optional>
#include <string>

#include "analysis/modal_state.hpp"
#include "analysis/shared_resources.hpp"
#include "analysis/spindle_state.hpp"
#include "support/errors.hpp"

namespace twinpost {

xz_box arc_box(double r_start, double z_start, double r_end, double z_end, double r_c, double z_c, bool cw) {
  xz_box b{std::min(r_start, r_end), std::max(r_start, r_end), std::min(z_start, z_end),
           std::max(z_start, z_end)};
  const double radius = std::hypot(r_start - r_c, z_start - z_c);
  // Angles with Z as the horizontal axis and r as the vertical one.
  const double a0 = std::atan2(r_start - r_c, z_start - z_c);
  const double a1 = std::atan2(r_end - r_c, z_end - z_c);
  constexpr double two_pi = 2 * std::numbers::pi;
  // The sweep counter-clockwise from the start: cw arcs are swept from the end instead.
  double from = cw ? a1 : a0, to = cw ? a0 : a1;
  double span = std::fmod(to - from + 2 * two_pi, two_pi);
  if (std::abs(r_start - r_end) < 1e-9 && std::abs(z_start - z_end) < 1e-9) span = two_pi;
  for (int q = 0; q < 4; ++q) {
    const double at = q * std::numbers::pi / 2;  // +z, +r, -z, -r
    if (std::fmod(at - from + 2 * two_pi, two_pi) <= span + 1e-12) {
      const double r = r_c + radius * std::sin(at), z = z_c + radius * std::cos(at);
      b.r0 = std::min(b.r0, r);
      b.r1 = std::max(b.r1, r);
      b.z0 = std::min(b.z0, z);
      b.z1 = std::max(b.z1, z);
    }
  }
  return b;
}

xz_box arc_box_radius(double r_start, double z_start, double r_end, double z_end, double radius, bool cw) {
  const double dr = r_end - r_start, dz = z_end - z_start, chord = std::hypot(dr, dz);
  const xz_box ends{std::min(r_start, r_end), std::max(r_start, r_end), std::min(z_start, z_end),
                    std::max(z_start, z_end)};
  if (chord < 1e-12 || std::abs(radius) < chord / 2 - 1e-9) return ends;  // no such arc: its ends
  const double h = std::sqrt(std::max(0.0, radius * radius - chord * chord / 4));
  // The centre of a clockwise minor arc (R > 0) lies to the left of the chord seen from the
  // start (z to the right, r up); a major arc's (R < 0) or a counter-clockwise one's to the right.
  const double sign = ((radius > 0) == cw) ? 1 : -1;
  const double rc = (r_start + r_end) / 2 + sign * h * (-dz) / chord;
  const double zc = (z_start + z_end) / 2 + sign * h * dr / chord;
  return arc_box(r_start, z_start, r_end, z_end, rc, zc, cw);
}

std::vector<xz_box> envelope_boxes(const interference_channel& e, const xz_box& tip) {
  std::vector<xz_box> out;
  for (const xz_box& b : e.boxes) {
    xz_box own{tip.r0 + b.r0, tip.r1 + b.r1, tip.z0 + b.z0, tip.z1 + b.z1};
    if (e.side < 0) own = {-own.r1, -own.r0, own.z0, own.z1};
    out.push_back(own);
  }
  return out;
}

double box_distance(const xz_box& a, const xz_box& b) {
  const double dr = std::max({0.0, a.r0 - b.r1, b.r0 - a.r1});
  const double dz = std::max({0.0, a.z0 - b.z1, b.z0 - a.z1});
  return std::hypot(dr, dz);
}

namespace {

// Consecutive sweeps are merged while the tip's box stays within this size (mm): the error of
// the model is at most this much, and a contour of many short moves keeps few boxes.
constexpr double merge_size = 2.0;
// The most boxes a segment keeps; beyond it neighbours are merged (coarser, never smaller).
constexpr std::size_t segment_cap = 4096;

// What one block (or a run of merged blocks) of a channel sweeps: 32 bytes, in floats (a
// micrometre at a metre), since a long job keeps many.
struct sweep {
  float r0, r1, z0, z1;  // the tip's box, r = X/2 as programmed
  int line;              // the first block's line
  float x, z;            // its point in messages (X as a diameter)
  std::uint16_t spindle;
  std::uint16_t tool;  // into channel_data::tools
  xz_box tip() const { return {r0, r1, z0, z1}; }
};

xz_box unite(const xz_box& a, const xz_box& b) {
  return {std::min(a.r0, b.r0), std::max(a.r1, b.r1), std::min(a.z0, b.z0), std::max(a.z1, b.z1)};
}

struct segment_data {
  // The open segment's sweeps. A closed one's go to the spill file (bounded memory however
  // long the programs are): `count` of them at `offset`, with the box around each spindle's.
  std::vector<sweep> sweeps;
  long offset = 0;
  std::uint32_t count = 0;
  bool spilled = false;
  std::vector<std::pair<std::uint16_t, xz_box>> around;  // per spindle: around its sweeps' tips
  int wait_code = 0;                                     // the wait that ends it (0: the program's end)
  int wait_line = 0;
};

struct channel_data {
  channel_data(const channel_spindles& spindles, const channel_modes& modes)
      : spindles(spindles), modes(modes) {}
  const interference_channel* env = nullptr;
  std::string file;                  // the program's name, as in messages
  const channel_spindles& spindles;  // the reading's (spindle_states), this block applied
  bool gms_only = spindles.needs_gms();
  // The reading's modal state (modal_states), this block applied: the motion, the cycle in
  // force (a lathe's single cycle, G90 G92 G94 in system A, modal as G1), G91, the unit, polar.
  const channel_modes& modes;
  double turning_z = 0;  // a single cycle's end Z, which its next passes keep (attack 63 M6: X28.4 alone)
  std::vector<segment_data> segments = std::vector<segment_data>(1);
  double x = 0, z = 0;
  // The second coordinate of the tip in the plane across the spindle axis: C under polar
  // interpolation (G12.1/G112: X and C a Cartesian plane on the face), else Y. 0 until given.
  double q = 0;
  bool known_x = false, known_z = false;
  // Millimetres per program unit (25.4 after G20): x, z and q are in program units, the sweeps'
  // boxes, the envelopes and the clearance in millimetres.
  double scale = 1;
  // The workpiece spindle the channel works on: the frame of its sweeps. A channel that turns
  // its live spindle (a milling tool) still works on the part in this one (issue 37, item 3).
  int work = -1;
  bool balance = false;  // in a balance cut: ordered by its own sync
  // The T words seen, as written ("0505"); [0] is none. `tool` is the one in force.
  std::vector<std::array<char, 12>> tools = std::vector<std::array<char, 12>>(1);
  std::uint16_t tool = 0;
  bool merge_open = false;  // the last sweep may take the next one
  long unplaced = 0;        // blocks moved by increments from a place not known: not held
  int unplaced_line = 0;    // the first of them
};

}  // namespace

bool interference_checked(const machine& m) {
  const auto with = std::count_if(m.channels.begin(), m.channels.end(), [&m](const channel_def& c) {
    return m.interference.channel(c.number) != nullptr;
  });
  return with >= 2 || !m.interference.zones.empty();
}

struct interference_check::impl {
  impl(const machine& mm, const spindle_states& spindles, const modal_states& modes) : m(mm) {
    for (const channel_def& c : m.channels) {
      channels.emplace_back(spindles.channel(c.number), modes.channel(c.number));
      channels.back().env = m.interference.channel(c.number);
      if (const spindle_def* live = m.spindle(c.live_spindle))
        live_spindles.push_back(static_cast<int>(live - m.spindles.data()));
    }
    for (channel_data& c : channels) {
      if (!is_live(c.spindles.current())) c.work = c.spindles.current();
      c.scale = c.modes.inch ? 25.4 : 1.0;
    }
    active = interference_checked(m);
    for (auto [code, into] :
         {std::pair{&m.codes.balance_on, &balance_on}, {&m.codes.balance_off, &balance_off}})
      if (const std::vector<nc_word> w = split_nc_words(*code); !w.empty() && w[0].numeric) *into = w[0];
  }

  ~impl() {
    if (spill) std::fclose(spill);
  }

  const machine& m;
  bool active = false;
  static constexpr std::size_t spill_buffer_size = std::size_t{1} << 16;
  std::unique_ptr<char[]> spill_buffer;  // the spill's stdio buffer (closed with it in ~impl)
  std::FILE* spill = nullptr;            // closed segments' sweeps (an anonymous temporary file)
  bool spill_failed = false;             // no temporary file: the sweeps stay in memory
  long spill_size = 0;                   // bytes written to it
  mutable bool spill_at_end = true;      // its position is its end (no reading since the last write)
  std::vector<channel_data> channels;
  std::vector<int> live_spindles;  // the channels' live spindles (indices into machine::spindles)
  std::optional<nc_word> balance_on, balance_off;

  bool is_live(int spindle) const {
    return std::find(live_spindles.begin(), live_spindles.end(), spindle) != live_spindles.end();
  }
  std::vector<std::vector<std::vector<int>>> clocks;   // [channel][segment][channel]
  mutable std::vector<interference_meeting> meetings;  // what meet() found, for pictures

  bool is_word(const nc_word& w, const std::optional<nc_word>& code) const {
    return code && w.address == code->address && w.numeric && w.number == code->number;
  }

  // `x`, `z`: the block's point in messages (a drilling cycle's: the hole's bottom).
  void add(channel_data& c, xz_box tip, int line, double x, double z) {
    tip = {tip.r0 * c.scale, tip.r1 * c.scale, tip.z0 * c.scale, tip.z1 * c.scale};
    std::vector<sweep>& s = c.segments.back().sweeps;
    const auto spindle = static_cast<std::uint16_t>(std::max(c.work, 0));
    if (c.merge_open && !s.empty() && s.back().spindle == spindle && s.back().tool == c.tool) {
      const xz_box u = unite(s.back().tip(), tip);
      if (u.r1 - u.r0 <= merge_size && u.z1 - u.z0 <= merge_size) {
        set_tip(s.back(), u);
        return;
      }
    }
    if (s.size() >= segment_cap) coarsen(s);
    sweep w{};
    set_tip(w, tip);
    w.line = line;
    w.x = static_cast<float>(x);
    w.z = static_cast<float>(z);
    w.spindle = spindle;
    w.tool = c.tool;
    s.push_back(w);
    c.merge_open = true;
  }

  // In floats: off by at most half a float's step (0.03 um at 1 m), nothing beside a clearance
  // of millimetres.
  static void set_tip(sweep& w, const xz_box& b) {
    w.r0 = static_cast<float>(b.r0);
    w.r1 = static_cast<float>(b.r1);
    w.z0 = static_cast<float>(b.z0);
    w.z1 = static_cast<float>(b.z1);
  }

  // Halves a segment's boxes by merging neighbours of one spindle and tool: bounded memory.
  static void coarsen(std::vector<sweep>& s) {
    std::size_t out = 0;
    for (std::size_t i = 0; i < s.size(); ++i) {
      if (out > 0 && (i % 2) == 1 && s[out - 1].spindle == s[i].spindle && s[out - 1].tool == s[i].tool)
        set_tip(s[out - 1], unite(s[out - 1].tip(), s[i].tip()));
      else
        s[out++] = s[i];
    }
    s.resize(out);
  }

  void block(const nc_block& b) {
    if (b.channel < 1 || static_cast<std::size_t>(b.channel) > channels.size()) return;
    channel_data& c = channels[static_cast<std::size_t>(b.channel - 1)];
    if (!c.env) return;
    if (c.file.empty()) c.file = b.file;  // one file per channel (its sections are joined)
    const std::vector<nc_word>& words = b.words();
    // (Only a block with G, M or S can select another spindle, where every work offset and
    // select code is one: spindle_states' gms_only. A work offset `E1`: attack 67 H6.)
    constexpr std::uint32_t gms = nc_letter('G') | nc_letter('M') | nc_letter('S');
    if (!c.gms_only || (b.letters() & gms))
      if (const int s = c.spindles.current(); s >= 0 && !is_live(s)) c.work = s;
    const nc_word *xw = nullptr, *zw = nullptr, *uw = nullptr, *ww = nullptr, *iw = nullptr, *kw = nullptr,
                  *rw = nullptr, *qw = nullptr, *jw = nullptr;
    // What the block's G codes did, read once for every rule (analysis/modal_state).
    const channel_modes& md = c.modes;
    const block_g_codes& g = md.now;
    // To (or from) the reference point, or in machine coordinates: out of the work area.
    const bool home = g.reference || g.machine;
    // A dwell, data or coordinate setting, a clamp, a macro call: no motion.
    const bool no_move = g.no_move, once = g.once, cycle = md.hole_cycle, turning = md.turning_cycle;
    if (g.any && g.units) {
      // The control keeps where the axes are: their values are said again in the new unit.
      const double to = md.inch ? 25.4 : 1.0;
      c.x *= c.scale / to, c.z *= c.scale / to, c.q *= c.scale / to;
      c.scale = to;
    }
    if (g.any && g.polar) c.q = 0;  // (off: the C axis is a rotation again; Y was not moved under polar)
    const bool polar = md.polar;
    for (const nc_word& w : words) {
      if (!w.numeric) continue;
      switch (w.address) {
        case 'G':
        case 'M':
          if (is_word(w, balance_on)) c.balance = true;
          if (is_word(w, balance_off)) c.balance = false;
          break;
        case 'T': {
          std::array<char, 12> t{};
          std::copy_n(w.value.begin(), std::min(w.value.size(), t.size() - 1), t.begin());
          auto at = static_cast<std::size_t>(std::find(c.tools.begin(), c.tools.end(), t) - c.tools.begin());
          if (at == c.tools.size()) {
            if (at < 65535)
              c.tools.push_back(t);
            else
              at = 0;  // more tools than the index holds: named by none
          }
          c.tool = static_cast<std::uint16_t>(at);
          break;
        }
        case 'X': xw = &w; break;
        case 'Z': zw = &w; break;
        case 'U': uw = &w; break;
        case 'W': ww = &w; break;
        case 'I': iw = &w; break;
        case 'K': kw = &w; break;
        case 'R': rw = &w; break;
        case 'J': jw = &w; break;
        case 'C':
          if (polar) qw = &w;
          break;
        case 'Y':
          if (!polar) qw = &w;
          break;
        default: break;
      }
    }
    if (home) {
      c.known_x = c.known_z = false;
      c.merge_open = false;
      return;
    }
    if (g.coordinate_setting && (xw || zw)) {
      // G50 X Z (G92 in systems B and C): the tool stands where the words say, in the frame they
      // set (attack 72 F3: it was left unknown, and a meeting after it passed).
      if (xw) c.x = xw->number, c.known_x = true;
      if (zw) c.z = zw->number, c.known_z = true;
      c.merge_open = false;
      return;
    }
    if (no_move || !(xw || zw || uw || ww || qw)) return;
    const double x0 = c.x, z0 = c.z, q0 = c.q;
    const bool known = c.known_x && c.known_z;
    if (md.incremental) {  // G91: every axis word an increment, as U and W are
      if (qw) c.q += qw->number;
      if (xw && c.known_x) c.x += xw->number;
      if (zw && c.known_z && !cycle) c.z += zw->number;
    } else {
      if (qw) c.q = qw->number;
      if (xw) c.x = xw->number, c.known_x = true;
      if (zw && !cycle) c.z = zw->number, c.known_z = true;
    }
    if (uw && c.known_x) c.x += uw->number;
    if (ww && c.known_z && !cycle) c.z += ww->number;
    if (turning && (zw || ww)) c.turning_z = c.z;
    if (turning && !zw && !ww && known) c.z = c.turning_z;
    if (!c.known_x || !c.known_z || c.balance) {
      // Increments from a place not known (after a reference return, G53, or from the start):
      // not held, and said (review 41 H3: a program in G91 throughout passed without a word).
      if (!c.balance && (uw || ww || (md.incremental && (xw || zw))) && c.unplaced++ == 0)
        c.unplaced_line = b.line;
      c.merge_open = false;
      return;
    }
    // Where the tip came from: unknown (after a reference return) means only the end point.
    const double rs = known ? x0 / 2 : c.x / 2, zs = known ? z0 : c.z;
    xz_box tip{std::min(rs, c.x / 2), std::max(rs, c.x / 2), std::min(zs, c.z), std::max(zs, c.z)};
    if (q0 != 0 || c.q != 0) {  // off the XZ plane: the tip's distance from the spindle axis
      const double qs = known ? q0 : c.q;
      const bool arc = known && (md.motion == 2 || md.motion == 3) && !cycle;
      planar_span(tip, rs, qs, c.x / 2, c.q, arc ? arc_radius(rs, qs, c.x / 2, c.q, iw, jw, kw, rw) : -1,
                  polar);
    }
    double shown_z = c.z;
    if (cycle && zw && !md.incremental) {  // down to the hole's bottom and back
      tip.z0 = std::min(tip.z0, zw->number);
      tip.z1 = std::max(tip.z1, zw->number);
      shown_z = zw->number;
    } else if (cycle && (ww || zw)) {
      // The depth by increments (W, or Z under G91): from the R level, itself R from where the
      // cycle starts (Fanuc), or from the start where the control reads R otherwise; both are
      // swept (attack 72 F1: the depth was lost, and a drill's meeting passed).
      const double depth = (ww ? ww : zw)->number, r = rw && rw->numeric ? rw->number : 0;
      for (const double bottom : {c.z + depth, c.z + r + depth}) {
        tip.z0 = std::min(tip.z0, bottom);
        tip.z1 = std::max(tip.z1, bottom);
      }
      shown_z = c.z + r + depth;
    } else if (known && (md.motion == 2 || md.motion == 3) && (iw || kw || rw) && q0 == 0 && c.q == 0) {
      tip = unite(tip, arc_of(x0 / 2, z0, c.x / 2, c.z, iw, kw, rw, md.motion == 2));
    }
    add(c, tip, b.line, c.x, shown_z);
    // A lathe cycle cuts to its end point and returns to where it began (analysis/nc_codes).
    if ((turning || once) && known) c.x = x0, c.z = z0;
  }

  // A move from (r0, q0) to (r1, q1) in the plane across the spindle axis (r = X/2, q = C under
  // polar interpolation or Y): `tip`'s r span becomes the span of the tip's distance from the
  // axis, on its own side (signed as X; under polar interpolation the X slide never passes the
  // axis, the part turns instead). `radius` >= 0: an arc of that radius (its points lie within
  // two radii of its start), -1: a line (its nearest point to the axis).
  static void planar_span(xz_box& tip, double r0, double q0, double r1, double q1, double radius,
                          bool polar) {
    const double d0 = std::hypot(r0, q0), d1 = std::hypot(r1, q1);
    double near = 0;
    if (radius >= 0) {
      near = std::max(0.0, std::min(d0, d1) - 2 * radius);
    } else {
      const double dr = r1 - r0, dq = q1 - q0, len2 = dr * dr + dq * dq;
      const double t = len2 > 0 ? std::clamp(-(r0 * dr + q0 * dq) / len2, 0.0, 1.0) : 0.0;
      near = std::hypot(r0 + t * dr, q0 + t * dq);
    }
    const double far = radius >= 0 ? std::max(d0, d1) + 2 * radius : std::max(d0, d1);
    if (polar || (r0 >= 0 && r1 >= 0)) {
      tip.r0 = near;
      tip.r1 = far;
    } else if (r0 <= 0 && r1 <= 0) {
      tip.r0 = -far;
      tip.r1 = -near;
    } else {  // across the axis
      tip.r0 = -far;
      tip.r1 = far;
    }
  }

  // The radius of an arc in the plane across the axis: |R|, else the length of its centre
  // offset (I, J or K as given), else half its chord (the smallest it can be).
  static double arc_radius(double r0, double q0, double r1, double q1, const nc_word* iw, const nc_word* jw,
                           const nc_word* kw, const nc_word* rw) {
    if (rw) return std::abs(rw->number);
    if (iw || jw || kw) {
      const double i = iw ? iw->number : 0, j = jw ? jw->number : 0, k = kw ? kw->number : 0;
      return std::sqrt(i * i + j * j + k * k);
    }
    return std::hypot(r1 - r0, q1 - q0) / 2;
  }

  // The box of an arc given by its centre (I, K: radius values from the start) or its radius R.
  static xz_box arc_of(double r0, double z0, double r1, double z1, const nc_word* iw, const nc_word* kw,
                       const nc_word* rw, bool cw) {
    if (iw || kw) return arc_box(r0, z0, r1, z1, r0 + (iw ? iw->number : 0), z0 + (kw ? kw->number : 0), cw);
    return arc_box_radius(r0, z0, r1, z1, rw->number, cw);
  }

  // A segment ends: the box around each spindle's sweeps kept, the sweeps to the spill file.
  void close(segment_data& seg) {
    for (const sweep& w : seg.sweeps) {
      auto at = std::find_if(seg.around.begin(), seg.around.end(),
                             [&](const auto& a) { return a.first == w.spindle; });
      if (at == seg.around.end())
        seg.around.emplace_back(w.spindle, w.tip());
      else
        at->second = unite(at->second, w.tip());
    }
    if (seg.sweeps.empty() || spill_failed) return;
    if (!spill) {
      if (!(spill = std::tmpfile())) {
        spill_failed = true;
        return;
      }
      // 64 KB a write, not the 4 KB glibc gives a buffer it allocates itself.
      spill_buffer = std::make_unique<char[]>(spill_buffer_size);
      std::setvbuf(spill, spill_buffer.get(), _IOFBF, spill_buffer_size);
    }
    // Written at the file's end, which this counts: a seek to it only after a reading (each
    // seek flushes and reads back the last block, four system calls per segment).
    if (!spill_at_end && std::fseek(spill, 0, SEEK_END) != 0) {
      spill_failed = true;
      return;
    }
    spill_at_end = true;
    seg.offset = spill_size;
    if (std::fwrite(seg.sweeps.data(), sizeof(sweep), seg.sweeps.size(), spill) != seg.sweeps.size()) {
      spill_failed = true;
      return;
    }
    spill_size += static_cast<long>(seg.sweeps.size() * sizeof(sweep));
    seg.count = static_cast<std::uint32_t>(seg.sweeps.size());
    seg.spilled = true;
    std::vector<sweep>().swap(seg.sweeps);
  }

  // A segment's sweeps: in memory, or read back from the spill file into `buf`.
  const std::vector<sweep>& sweeps_of(const segment_data& seg, std::vector<sweep>& buf) const {
    if (!seg.spilled) return seg.sweeps;
    buf.resize(seg.count);
    spill_at_end = false;
    if (std::fflush(spill) != 0 || std::fseek(spill, seg.offset, SEEK_SET) != 0 ||
        std::fread(buf.data(), sizeof(sweep), buf.size(), spill) != buf.size())
      throw config_error("cannot read back the interference check's temporary file");
    return buf;
  }

  static bool empty(const segment_data& seg) { return seg.sweeps.empty() && seg.count == 0; }

  void wait(const nc_wait& w) {
    if (w.channel < 1 || static_cast<std::size_t>(w.channel) > channels.size()) return;
    channel_data& c = channels[static_cast<std::size_t>(w.channel - 1)];
    c.segments.back().wait_code = w.code;
    c.segments.back().wait_line = w.where.line;
    close(c.segments.back());
    c.segments.emplace_back();
    c.merge_open = false;
  }

  // --- happens-before (as analysis/shared_resources) ---------------------------------------

  void make_clocks(const std::vector<std::uint64_t>& rendezvous) {
    clocks = segment_clocks(rendezvous, channels.size());
  }

  int over(int channel, std::size_t seg, int of) const {
    const auto& cl = clocks[static_cast<std::size_t>(channel - 1)];
    return seg < cl.size() ? cl[seg][static_cast<std::size_t>(of - 1)] : -1;
  }

  // --- the rules ---------------------------------------------------------------------------

  std::string where(const channel_data& c, const sweep& s) const {
    const char* t = c.tools[s.tool].data();
    return fmt::format("{}X{:g} Z{:g}", t[0] ? fmt::format("T{} at ", t) : std::string(), s.x, s.z);
  }
  std::string between(const channel_data& c, std::size_t seg) const {
    // The waits as file:line places: post moves them to their CL records (post/sync_at_cl).
    const std::string from = seg == 0
                                 ? std::string("its start")
                                 : fmt::format("{}{} ({}:{})", m.waits.address, c.segments[seg - 1].wait_code,
                                               c.file, c.segments[seg - 1].wait_line);
    const std::string to = c.segments[seg].wait_code
                               ? fmt::format("{}{} ({}:{})", m.waits.address, c.segments[seg].wait_code,
                                             c.file, c.segments[seg].wait_line)
                               : std::string("its end");
    return fmt::format("between {} and {}", from, to);
  }

  struct placed {
    xz_box box;
    const sweep* s;
  };
  // The `k`-th box of the channel's envelope around each sweep on `spindle`, sorted along Z.
  std::vector<placed> place(const channel_data& c, const std::vector<sweep>& sweeps, int spindle,
                            std::size_t k) const {
    std::vector<placed> out;
    for (const sweep& s : sweeps)
      if (s.spindle == spindle) out.push_back({envelope_boxes(*c.env, s.tip())[k], &s});
    std::sort(out.begin(), out.end(), [](const placed& p, const placed& q) { return p.box.z0 < q.box.z0; });
    return out;
  }

  // The first pair of boxes of two segments closer than the clearance: a sweep along Z.
  std::optional<std::pair<const placed*, const placed*>> first_meeting(const std::vector<placed>& a,
                                                                       const std::vector<placed>& b,
                                                                       double& distance) const {
    const double cl = m.interference.clearance;
    double longest = 0;  // no box of b is longer along Z: those starting before are too far
    for (const placed& q : b) longest = std::max(longest, q.box.z1 - q.box.z0);
    std::size_t start = 0;
    for (const placed& p : a) {
      while (start < b.size() && b[start].box.z0 + longest < p.box.z0 - cl) ++start;
      for (std::size_t j = start; j < b.size() && b[j].box.z0 < p.box.z1 + cl; ++j) {
        const double d = box_distance(p.box, b[j].box);
        if (d < cl) {
          distance = d;
          return std::pair{&p, &b[j]};
        }
      }
    }
    return std::nullopt;
  }

  void pair_rule(std::vector<diagnostic>& out) const {
    const int n = static_cast<int>(channels.size());
    for (int a = 1; a <= n; ++a)
      for (int b = a + 1; b <= n; ++b) {
        const channel_data& ca = channels[static_cast<std::size_t>(a - 1)];
        const channel_data& cb = channels[static_cast<std::size_t>(b - 1)];
        if (!ca.env || !cb.env) continue;
        for (std::size_t i = 0; i < ca.segments.size(); ++i) {
          if (empty(ca.segments[i]) || over(a, i, b) < 0) continue;
          for (auto j = static_cast<std::size_t>(over(a, i, b)); j < cb.segments.size(); ++j) {
            const int b_over_a = over(b, j, a);
            if (b_over_a < 0 || static_cast<int>(i) < b_over_a) break;  // a's segment ends before b's
            if (!empty(cb.segments[j])) meet(ca, a, i, cb, b, j, out);
          }
        }
      }
  }

  void meet(const channel_data& ca, int a, std::size_t i, const channel_data& cb, int b, std::size_t j,
            std::vector<diagnostic>& out) const {
    for (std::size_t s = 0; s < m.spindles.size(); ++s) {
      // Most concurrent work stays apart as a whole (an upper and a lower turret, each on its
      // side of the axis): the boxes around all of each interval's sweeps say so at once.
      const auto around = [&](const segment_data& seg, const interference_channel& e) {
        std::optional<xz_box> u;
        for (const auto& [spindle, box] : seg.around)
          if (spindle == s) u = box;
        if (!u) return u;
        const std::vector<xz_box> boxes = envelope_boxes(e, *u);
        xz_box all = boxes.front();
        for (const xz_box& x : boxes) all = unite(all, x);
        return std::optional<xz_box>(all);
      };
      const std::optional<xz_box> ua = around(ca.segments[i], *ca.env);
      if (!ua) continue;
      const std::optional<xz_box> ub = around(cb.segments[j], *cb.env);
      if (!ub || box_distance(*ua, *ub) >= m.interference.clearance) continue;
      // Box by box of the envelopes (each kind alike in size: the sweep along Z stays narrow).
      double d = 0;
      std::optional<std::pair<const placed*, const placed*>> hit;
      std::vector<sweep> buf_a, buf_b;  // the sweeps read back (the hits point into them)
      const std::vector<sweep>& sa = sweeps_of(ca.segments[i], buf_a);
      const std::vector<sweep>& sb = sweeps_of(cb.segments[j], buf_b);
      std::vector<std::vector<placed>> pbs;
      for (std::size_t kb = 0; kb < cb.env->boxes.size(); ++kb)
        pbs.push_back(place(cb, sb, static_cast<int>(s), kb));
      std::vector<placed> pa;
      for (std::size_t ka = 0; ka < ca.env->boxes.size() && !hit; ++ka) {
        pa = place(ca, sa, static_cast<int>(s), ka);
        // Complete in one direction: every box of b near one of a in Z is looked at.
        for (std::size_t kb = 0; kb < pbs.size() && !hit; ++kb) hit = first_meeting(pa, pbs[kb], d);
      }
      if (!hit) continue;
      const sweep& x = *hit->first->s;
      const sweep& y = *hit->second->s;
      const auto mirrored = [](const interference_channel& e, const xz_box& t) {
        return e.side < 0 ? xz_box{-t.r1, -t.r0, t.z0, t.z1} : t;
      };
      meetings.push_back({a, b, m.spindles[s].name, mirrored(*ca.env, x.tip()), mirrored(*cb.env, y.tip()),
                          envelope_boxes(*ca.env, x.tip()), envelope_boxes(*cb.env, y.tip()), d, ca.file,
                          cb.file, x.line, y.line});
      out.push_back(
          {severity::error,
           ca.file,
           x.line,
           1,
           fmt::format("channel {} ({}) may meet channel {} ({}, {}:{}) on the {} spindle, {} of channel {}: "
                       "{:.1f} mm apart, {:g} mm required; no wait orders the two blocks",
                       a, where(ca, x), b, where(cb, y), cb.file, y.line, m.spindles[s].name, between(ca, i),
                       a, d, m.interference.clearance),
           {}});
      out.push_back(
          {severity::note, cb.file, y.line, 1, fmt::format("channel {} is here ({})", b, where(cb, y)), {}});
      return;  // one finding for each pair of segments
    }
  }

  void zone_rule(std::vector<diagnostic>& out) const {
    for (std::size_t k = 0; k < channels.size(); ++k) {
      const channel_data& c = channels[k];
      if (!c.env) continue;
      for (const interference_zone& z : m.interference.zones) {
        const spindle_def* sp = m.spindle(z.spindle);
        const int si = static_cast<int>(sp - m.spindles.data());
        const xz_box sides[2] = {z.box, {-z.box.r1, -z.box.r0, z.box.z0, z.box.z1}};
        bool found = false;
        std::vector<sweep> buf;
        for (std::size_t seg = 0; seg < c.segments.size() && !found; ++seg)
          for (const sweep& s : sweeps_of(c.segments[seg], buf)) {
            if (s.spindle != si) continue;
            for (const xz_box& e : envelope_boxes(*c.env, s.tip()))
              for (const xz_box& zb : sides)
                if (!found && box_distance(e, zb) < m.interference.clearance) {
                  found = true;
                  out.push_back(
                      {severity::error,
                       c.file,
                       s.line,
                       1,
                       fmt::format("channel {} ({}) comes within {:.1f} mm of the {} spindle's static "
                                   "zone [{:g}, {:g}, {:g}, {:g}] (interference.zone), {:g} mm required",
                                   k + 1, where(c, s), box_distance(e, zb), z.spindle, z.box.r0, z.box.r1,
                                   z.box.z0, z.box.z1, m.interference.clearance),
                       {}});
                }
            if (found) break;
          }
      }
    }
  }
};

void fill_source_lines(std::vector<diagnostic>& found, const std::vector<nc_source>& files,
                       const machine& m) {
  if (std::none_of(found.begin(), found.end(),
                   [](const diagnostic& d) { return d.line > 0 && d.source_line.empty(); }))
    return;
  nc_read_options o;
  o.on_block = [&found](const nc_block& b) {
    for (diagnostic& d : found)
      if (d.line == b.line && d.source_line.empty() && d.file == b.file) d.source_line = std::string(b.text);
  };
  diagnostic_list ignored;
  read_nc_programs(files, m, ignored, o);
}

interference_check::interference_check(const machine& m, const spindle_states& spindles,
                                       const modal_states& modes)
    : p_(std::make_unique<impl>(m, spindles, modes)) {}
interference_check::~interference_check() = default;
bool interference_check::active() const { return p_->active; }
const std::vector<interference_meeting>& interference_check::meetings() const { return p_->meetings; }
void interference_check::block(const nc_block& b) { p_->block(b); }
void interference_check::wait(const nc_wait& w) { p_->wait(w); }

std::vector<diagnostic> interference_check::finish(const std::vector<std::uint64_t>& rendezvous,
                                                   bool waits_sound) {
  std::vector<diagnostic> out;
  if (!p_->active) return out;
  for (channel_data& c : p_->channels) p_->close(c.segments.back());
  for (std::size_t i = 0; i < p_->channels.size(); ++i)
    if (const channel_data& c = p_->channels[i]; c.unplaced > 0)
      out.push_back({severity::warning,
                     c.file,
                     c.unplaced_line,
                     1,
                     fmt::format("channel {}: {} block{} from here on move{} by increments from a place the "
                                 "interference rule does not know (the program's start, a reference return "
                                 "or a move in machine coordinates): not held to the other channels; give X "
                                 "and Z absolute first",
                                 i + 1, c.unplaced, c.unplaced == 1 ? "" : "s", c.unplaced == 1 ? "s" : ""),
                     {}});
  p_->zone_rule(out);
  if (!waits_sound) return out;
  p_->make_clocks(rendezvous);
  p_->pair_rule(out);
  return out;
}

}  // namespace twinpost
