#pragma once
// The twin-turret lathe benchmark job (lathe2): HEAD/1 and HEAD/2 sections alternate, each
// one turning operation:
//
//   HEAD/h
//   TURRET/t,t
//   SPINDL/SMM,200,MAXRPM,3000,CLW
//   FEDRAT/0.25,MMPR
//   RAPID / GOTO/x,0,z ...            roughing passes along -Z, Y = 0, X as radius; the
//                                     HEAD/2 turret (a lower one) works at x < 0
//   CIRCLE/xc,0,zc,0,+-1,0,r + GOTO   arcs in the XZ plane (counter-clockwise about the
//                                     normal, as CATIA and Creo mean it)
//   SYNC/k,1,2                        the same sync indices, in the same order, in the
//                                     HEAD/1 and the HEAD/2 section of each pair
//
// The last pair ends each head with END, and FINI closes the file. A CATIA-style banner
// makes dialect detection pick CATIA. Z stays positive (part face at Z152, chuck side
// towards Z0) so that positions sit inside the Z 0..800 travel of the built-in
// twin-turret lathes.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "cl_writer.hpp"

namespace bench {

class lathe_job {
 public:
  lathe_job(record_writer& w, random_source& rng) : w_(w), rng_(rng) {
    heads_[0].number = 1;
    heads_[1].number = 2;
    heads_[1].x_cut = 38;
    heads_[1].side = -1;  // the lower turret: its tools sit below the spindle centre
  }

  /// Writes a whole job of exactly `records` records (at least `minimum_records`).
  void write(std::uint64_t records, std::uint64_t seed) {
    budget_ = records - 1;  // FINI
    w_.record("$$ -----------------------------------------------------------------");
    w_.text("$$     CATIA APT VERSION 1.0 - twinpost benchmark job lathe2: ");
    w_.integer(static_cast<long>(records)).text(" records, seed ").integer(static_cast<long>(seed));
    w_.end_record();
    w_.record("$$ -----------------------------------------------------------------");
    w_.record("PARTNO BENCH_LATHE2");
    w_.record("UNITS/MM");
    while (w_.records() < budget_) pair();
    w_.record("FINI");
  }

  static constexpr std::uint64_t minimum_records = 32;

 private:
  static constexpr double z_clear = 154, z_face = 152, x_stock = 45, x_min = 10;
  static constexpr std::uint64_t min_moves = 3;  // RAPID + GOTO approach, one cut

  enum class phase { approach, engage, turn, retract, back };

  struct head_state {
    int number = 1;
    double side = 1;  // the sign of x in the CL: the geometry below is worked out for +x
    grid_point pos = grid_point::of(x_stock + 5, 0, z_clear + 20);
    double x_cut = x_stock - 1;
    double z_end = 100;
    phase at = phase::approach;
  };

  // A HEAD/1 section and a HEAD/2 section with the same sync points.
  void pair() {
    std::uint64_t remaining = budget_ - w_.records();
    std::uint64_t syncs = static_cast<std::uint64_t>(rng_.between(1, 3));
    std::uint64_t m1 = static_cast<std::uint64_t>(rng_.between(200, 3000));
    std::uint64_t m2 = static_cast<std::uint64_t>(rng_.between(200, 3000));
    std::uint64_t overhead = 2 * (4 + syncs);
    bool last = overhead + m1 + m2 + 1000 > remaining;  // leave room for a whole pair, or end
    if (last) {
      overhead += 2;  // END in each head
      while (syncs > 1 && remaining < overhead + 2 * min_moves) {
        --syncs;
        overhead -= 2;
      }
      std::uint64_t moves = remaining - overhead;
      m1 = moves / 2;
      m2 = moves - m1;
    }
    section(heads_[0], m1, syncs, last);
    section(heads_[1], m2, syncs, last);
    next_sync_ += static_cast<long>(syncs);
  }

  // One head's operation: exactly `moves` motion records plus `syncs` SYNC records.
  void section(head_state& h, std::uint64_t moves, std::uint64_t syncs, bool last) {
    w_.text("HEAD/").integer(h.number);
    w_.end_record();
    long tool = rng_.between(1, 12);
    w_.text("TURRET/").integer(tool).text(",").integer(tool);
    w_.end_record();
    w_.record("SPINDL/SMM,200,MAXRPM,3000,CLW");
    w_.record("FEDRAT/0.25,MMPR");
    std::vector<std::uint64_t> at(syncs);
    for (auto& a : at) a = static_cast<std::uint64_t>(rng_.between(0, static_cast<long>(moves)));
    std::sort(at.begin(), at.end());
    h.at = phase::approach;
    std::uint64_t done = 0, s = 0;
    while (done < moves) {
      while (s < syncs && at[s] <= done) sync(s++);
      done += item(h, moves - done);
    }
    while (s < syncs) sync(s++);
    if (last) w_.record("END");
  }

  void sync(std::uint64_t s) {
    w_.text("SYNC/").integer(next_sync_ + static_cast<long>(s)).text(",1,2");
    w_.end_record();
  }

  // A point as the head's CL gives it: x negated on the lower turret (exactly: grid units).
  static grid_point mirrored(const head_state& h, grid_point p) {
    if (h.side < 0) p.x = -p.x;
    return p;
  }

  void go(head_state& h, double x, double z) {
    h.pos = grid_point::of(x, 0, z);
    w_.text("GOTO/");
    put_xyz(w_, mirrored(h, h.pos));
    w_.end_record();
  }

  // One step of the roughing cycle, at most `left` records; returns the records written.
  std::uint64_t item(head_state& h, std::uint64_t left) {
    double x = h.pos.dx(), z = h.pos.dz();
    if (left < 2 && (h.at == phase::approach || h.at == phase::back)) {
      go(h, x, z > x_min + 1 ? z - 0.05 : z + 0.05);  // the budget ends here: a short move
      return 1;
    }
    switch (h.at) {
      case phase::approach:
        w_.record("RAPID");
        go(h, h.x_cut + 1, z_clear);
        h.at = phase::engage;
        return 2;
      case phase::engage:
        go(h, h.x_cut, z_clear);
        h.z_end = rng_.uniform(40, 130);
        h.at = phase::turn;
        return 1;
      case phase::turn:
        if (left >= 2 && rng_.chance(0.03) && arc(h)) return 2;
        if (z <= h.z_end) {
          h.at = phase::retract;
          return item(h, left);
        }
        go(h, h.x_cut + rng_.uniform(-0.05, 0.05), std::max(z - rng_.uniform(0.3, 2.5), h.z_end));
        return 1;
      case phase::retract:
        go(h, x + 1, z);
        h.at = phase::back;
        return 1;
      case phase::back:
        w_.record("RAPID");
        go(h, x, z_clear);
        h.x_cut -= rng_.uniform(1.0, 2.5);
        if (h.x_cut < x_min + 2) h.x_cut = x_stock - 1;  // next part
        h.at = phase::engage;
        return 2;
    }
    return 0;
  }

  // CIRCLE in the XZ plane plus its end point; false if the arc would leave the work area.
  bool arc(head_state& h) {
    double r = rng_.uniform(0.5, 4.0);
    exact_angle start = pick_angle(rng_), sweep = pick_angle(rng_);
    double v[3] = {r * start.cos, 0, r * start.sin};  // centre to start point
    if (rng_.chance(0.5)) v[2] = -v[2];
    double side = rng_.chance(0.5) ? 1.0 : -1.0;
    for (int attempt = 0; attempt < 2; ++attempt, side = -side) {
      double n[3] = {0, side, 0};
      double e[3];
      rotate_about(n, v, sweep, e);
      double cx = h.pos.dx() - v[0], cz = h.pos.dz() - v[2];
      double ex = cx + e[0], ez = cz + e[2];
      if (cx <= 0 || ex < x_min || ex > x_stock + 2 || ez < h.z_end - 5 || ez > z_clear) continue;
      // Mirrored in x (HEAD/2), the same arc turns the other way about the same normal.
      w_.text("CIRCLE/");
      put_xyz(w_, mirrored(h, grid_point::of(cx, 0, cz)));
      w_.text(",0.0000000,").number(side * h.side, 7).text(",0.0000000,").number(r, 4);
      w_.end_record();
      go(h, ex, ez);
      return true;
    }
    return false;
  }

  record_writer& w_;
  random_source& rng_;
  std::uint64_t budget_ = 0;
  head_state heads_[2];
  long next_sync_ = 1;
};

}  // namespace bench
