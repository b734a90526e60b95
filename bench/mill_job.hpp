#pragma once
// Milling benchmark jobs in NX CLSF-like syntax: a raster finish over a smooth surface.
//
//   mill3  GOTO/x,y,z (4 decimals); line ends turn round with an NX CIRCLE (11 values,
//          clockwise about i,j,k) + GOTO, or retract, move over and plunge with RAPID and a
//          plunge feed; now and then a blend arc mid-line and a tool change.
//   mill5  the same raster under MULTAX/ON with GOTO/x,y,z,i,j,k: the tool axis follows
//          the surface normal (unit vector, 7 decimals). No arcs: 5-axis finishing is all
//          GOTO.
//
// The record budget is exact: items that would overshoot it give way to single GOTOs.
#include <cstdint>

#include "cl_writer.hpp"

namespace bench {

class mill_job {
 public:
  mill_job(record_writer& w, random_source& rng, bool five_axis) : w_(w), rng_(rng), five_(five_axis) {}

  /// Writes a whole job of exactly `records` records (at least `minimum_records`).
  void write(std::uint64_t records, std::uint64_t seed) {
    budget_ = records - 2;  // END, FINI
    header(records, seed);
    while (w_.records() < budget_) step();
    w_.record("END");
    w_.record("FINI");
  }

  static constexpr std::uint64_t minimum_records = 24;

 private:
  static constexpr double x_min = 0, x_max = 200, y_min = 0, y_max = 150, z_safe = 25;
  static constexpr long feed_cut = 1200, feed_plunge = 300;

  void header(std::uint64_t records, std::uint64_t seed) {
    w_.text("$$ twinpost benchmark job ").text(five_ ? "mill5" : "mill3").text(": ");
    w_.integer(static_cast<long>(records)).text(" records, seed ").integer(static_cast<long>(seed));
    w_.end_record();
    w_.record("UNITS/MM");
    if (five_) w_.record("MULTAX/ON");
    w_.record(five_ ? "TOOL PATH/BENCH_FLOWCUT,TOOL,BALL-10MM" : "TOOL PATH/BENCH_ZIGZAG,TOOL,BALL-10MM");
    w_.record("TLDATA/MILL,10.0000,5.0000,75.0000,0.0000,0.0000");
    w_.record("MSYS/0.0000,0.0000,0.0000,1.0000000,0.0000000,0.0000000,0.0000000,1.0000000,0.0000000");
    w_.record("$$ centerline data");
    w_.record("LOADTL/1");
    w_.record("SPINDL/RPM,8000,CLW");
    feed(feed_cut);
    rapid_to(x_min, y_min, z_safe);
  }

  // The surface the tool rides on, and its slopes (for the 5-axis tool axis).
  double surface(double x, double y) const {
    double u = (x - 100) / 100, v = (y - 75) / 75;
    return five_ ? 30 * (u * u - 0.5 * v * v) - 10 : -2 - 6 * u * u + 4 * v * v;
  }
  void slopes(double x, double y, double& fx, double& fy) const {
    double u = (x - 100) / 100, v = (y - 75) / 75;
    fx = five_ ? 60 * u / 100 : -12 * u / 100;
    fy = five_ ? -30 * v / 75 : 8 * v / 75;
  }

  void feed(long mmpm) {
    w_.text("FEDRAT/MMPM,").fixed(mmpm * 10000, 4);
    w_.end_record();
  }

  // GOTO/x,y,z[,i,j,k] to a point; the 5-axis tool axis is the surface normal, jittered.
  void go(double x, double y, double z) {
    pos_ = grid_point::of(x, y, z);
    w_.text("GOTO/");
    put_xyz(w_, pos_);
    if (five_) {
      double fx, fy;
      slopes(x, y, fx, fy);
      double i = -fx + rng_.uniform(-0.01, 0.01), j = -fy + rng_.uniform(-0.01, 0.01), k = 1;
      double len = std::sqrt(i * i + j * j + k * k);
      w_.text(",").number(i / len, 7).text(",").number(j / len, 7).text(",").number(k / len, 7);
    }
    w_.end_record();
  }
  void rapid_to(double x, double y, double z) {
    w_.record("RAPID");
    go(x, y, z);
  }
  bool fits(std::uint64_t n) const { return w_.records() + n <= budget_; }

  // One item of the toolpath: a cutting step, a line end, a blend arc or a tool change.
  void step() {
    if (!five_ && rng_.chance(0.01) && fits(2) && blend_arc()) return;
    if (rng_.chance(0.00002) && fits(6)) return tool_change();
    double nx = x_ + dir_ * rng_.uniform(five_ ? 0.2 : 0.3, five_ ? 1.0 : 1.5);
    if (nx < x_min || nx > x_max) return line_end();
    x_ = nx;
    go(x_, y_, surface(x_, y_) + rng_.uniform(-0.02, 0.02));
  }

  // At the end of a raster line: an arc turnaround (mill3) or retract, move over, plunge.
  void line_end() {
    double r = rng_.uniform(0.25, 1.0);
    if (!five_ && y_ + 2 * r <= y_max && rng_.chance(0.5) && fits(2)) {
      // A half circle outside the part edge. NX goes clockwise about i,j,k, so the normal
      // points down at the right-hand edge (counter-clockwise seen from above).
      double n[3] = {0, 0, dir_ > 0 ? -1.0 : 1.0};
      grid_point c = grid_point::of(pos_.dx(), pos_.dy() + r, pos_.dz());
      circle(c, n, r);
      go(pos_.dx(), pos_.dy() + 2 * r, pos_.dz());
      y_ = pos_.dy();
      dir_ = -dir_;
      return;
    }
    if (!fits(7)) {  // budget nearly spent: keep cutting on the spot
      dir_ = -dir_;
      go(x_, y_, surface(x_, y_));
      return;
    }
    y_ += 2 * r;
    if (y_ > y_max) y_ = y_min;
    rapid_to(pos_.dx(), pos_.dy(), z_safe);
    rapid_to(x_, y_, z_safe);
    feed(feed_plunge);
    go(x_, y_, surface(x_, y_));
    feed(feed_cut);
    dir_ = -dir_;
  }

  // A small arc that wanders off the raster line and back into the cut.
  bool blend_arc() {
    double r = rng_.uniform(0.5, 3.0);
    exact_angle a = pick_angle(rng_);
    double n[3] = {0, 0, rng_.chance(0.5) ? 1.0 : -1.0};
    double v[3] = {0, -dir_ * r * n[2], 0};  // centre to start, perpendicular to the line
    double m[3] = {-n[0], -n[1], -n[2]};     // NX: clockwise about n
    double e[3];
    rotate_about(m, v, a, e);
    double cx = pos_.dx() - v[0], cy = pos_.dy() - v[1];
    double ex = cx + e[0], ey = cy + e[1];
    if (ex < x_min || ex > x_max || ey < y_min || ey > y_max) return false;
    circle(grid_point::of(cx, cy, pos_.dz()), n, r);
    go(ex, ey, pos_.dz());
    x_ = ex;
    y_ = ey;
    return true;
  }

  // CIRCLE/xc,yc,zc,i,j,k,r,tol,?,tool diameter,? as NX writes it.
  void circle(const grid_point& c, const double n[3], double r) {
    w_.text("CIRCLE/");
    put_xyz(w_, c);
    w_.text(",").number(n[0], 7).text(",").number(n[1], 7).text(",").number(n[2], 7);
    w_.text(",").number(r, 4).text(",0.0600,0.5000,10.0000,0.0000");
    w_.end_record();
  }

  void tool_change() {
    rapid_to(pos_.dx(), pos_.dy(), z_safe);
    // NX writes each tool's TLDATA before its LOADTL: its length places a 5-axis head's joints.
    w_.record("TLDATA/MILL,10.0000,5.0000,75.0000,0.0000,0.0000");
    w_.text("LOADTL/").integer(++tool_);
    w_.end_record();
    w_.text("SPINDL/RPM,").integer(rng_.between(60, 120) * 100).text(",CLW");
    w_.end_record();
    feed(feed_cut);
  }

  record_writer& w_;
  random_source& rng_;
  bool five_;
  std::uint64_t budget_ = 0;
  grid_point pos_;
  double x_ = x_min, y_ = y_min;
  int dir_ = 1;
  long tool_ = 1;
};

}  // namespace bench
