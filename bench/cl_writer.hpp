#pragma once
// The pieces every benchmark job is made of: a fixed-seed random source and a buffered
// writer that counts CL records and prints fixed-point numbers.
//
// Byte-identical output across runs and machines: the random source is integer-only
// (splitmix64), geometry uses only + - * / and sqrt (correctly rounded in IEEE 754), no
// sin/cos from libm, and every printed number goes through std::llround into an integer
// and is written digit by digit. No locale, no printf.
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace bench {

/// splitmix64 (Steele, Lea, Flood 2014): tiny, fast, fixed sequence for a given seed.
class random_source {
 public:
  explicit random_source(std::uint64_t seed) : state_(seed) {}

  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  /// An integer in [lo, hi]. The modulo bias is far below anything a benchmark notices.
  long between(long lo, long hi) {
    return lo + static_cast<long>(next() % static_cast<std::uint64_t>(hi - lo + 1));
  }
  /// A double in [0, 1).
  double unit() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  /// A double in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * unit(); }
  /// True with probability `p`.
  bool chance(double p) { return unit() < p; }

 private:
  std::uint64_t state_;
};

/// Writes CL text to a stdio file through a large buffer and counts logical records.
/// Every record is exactly one physical line (no `$` continuations), so the record count
/// equals the line count.
class record_writer {
 public:
  explicit record_writer(std::FILE* out) : out_(out) { buf_.reserve(capacity + 256); }
  ~record_writer() {
    try {
      flush();
    } catch (...) {  // the caller flushes explicitly and sees the error there
    }
  }
  record_writer(const record_writer&) = delete;
  record_writer& operator=(const record_writer&) = delete;

  /// Appends raw text to the current record.
  record_writer& text(std::string_view s) {
    buf_.insert(buf_.end(), s.begin(), s.end());
    return *this;
  }
  /// Appends `value / 10^decimals` with exactly `decimals` digits after the point.
  /// A value that rounds to zero prints without a sign.
  record_writer& fixed(std::int64_t value, int decimals) {
    char tmp[32];
    int n = 0;
    bool negative = value < 0;
    std::uint64_t v = negative ? 0 - static_cast<std::uint64_t>(value) : static_cast<std::uint64_t>(value);
    for (int i = 0; i < decimals; ++i) {
      tmp[n++] = static_cast<char>('0' + v % 10);
      v /= 10;
    }
    if (decimals > 0) tmp[n++] = '.';
    do {
      tmp[n++] = static_cast<char>('0' + v % 10);
      v /= 10;
    } while (v != 0);
    if (negative) tmp[n++] = '-';
    while (n > 0) buf_.push_back(tmp[--n]);
    return *this;
  }
  /// Appends a double rounded to `decimals` digits.
  record_writer& number(double value, int decimals) { return fixed(to_fixed(value, decimals), decimals); }
  /// Appends a whole number.
  record_writer& integer(long value) { return fixed(value, 0); }
  /// Ends the current record (one line) and counts it.
  void end_record() {
    buf_.push_back('\n');
    ++records_;
    if (buf_.size() >= capacity) flush();
  }
  /// Writes a whole record.
  void record(std::string_view s) {
    text(s);
    end_record();
  }

  std::uint64_t records() const { return records_; }

  void flush() {
    if (buf_.empty()) return;
    if (std::fwrite(buf_.data(), 1, buf_.size(), out_) != buf_.size())
      throw std::runtime_error(std::string("write failed: ") + std::strerror(errno));
    buf_.clear();
  }

  /// `value` in units of 10^-decimals, rounded half away from zero.
  static std::int64_t to_fixed(double value, int decimals) {
    double scale = 1;
    for (int i = 0; i < decimals; ++i) scale *= 10;
    return static_cast<std::int64_t>(std::llround(value * scale));
  }

 private:
  static constexpr std::size_t capacity = 1 << 20;
  std::FILE* out_;
  std::vector<char> buf_;
  std::uint64_t records_ = 0;
};

/// A point on the 0.0001 mm grid: what was printed is exactly what the next move starts from.
struct grid_point {
  std::int64_t x = 0, y = 0, z = 0;  ///< units of 0.0001 mm

  static grid_point of(double x, double y, double z) {
    return {record_writer::to_fixed(x, 4), record_writer::to_fixed(y, 4), record_writer::to_fixed(z, 4)};
  }
  double dx() const { return static_cast<double>(x) * 1e-4; }
  double dy() const { return static_cast<double>(y) * 1e-4; }
  double dz() const { return static_cast<double>(z) * 1e-4; }
};

/// Writes `x,y,z` with 4 decimals.
inline void put_xyz(record_writer& w, const grid_point& p) {
  w.fixed(p.x, 4).text(",").fixed(p.y, 4).text(",").fixed(p.z, 4);
}

/// A rotation angle with an exact rational cosine and sine (a Pythagorean triple), so an
/// arc end point needs no libm trigonometry.
struct exact_angle {
  double cos, sin;
};

/// Rotates `v` (perpendicular to the unit vector `n`) by `a`, counter-clockwise about `n`.
inline void rotate_about(const double n[3], const double v[3], exact_angle a, double out[3]) {
  double c[3] = {n[1] * v[2] - n[2] * v[1], n[2] * v[0] - n[0] * v[2], n[0] * v[1] - n[1] * v[0]};
  for (int i = 0; i < 3; ++i) out[i] = v[i] * a.cos + c[i] * a.sin;
}

/// Angles between about 16 and 180 degrees, all exact.
inline exact_angle pick_angle(random_source& rng) {
  static constexpr exact_angle table[] = {{24.0 / 25, 7.0 / 25},
                                          {12.0 / 13, 5.0 / 13},
                                          {4.0 / 5, 3.0 / 5},
                                          {15.0 / 17, 8.0 / 17},
                                          {3.0 / 5, 4.0 / 5},
                                          {5.0 / 13, 12.0 / 13},
                                          {7.0 / 25, 24.0 / 25},
                                          {0.0, 1.0},
                                          {-3.0 / 5, 4.0 / 5},
                                          {-4.0 / 5, 3.0 / 5},
                                          {-1.0, 0.0}};
  return table[rng.between(0, sizeof table / sizeof table[0] - 1)];
}

}  // namespace bench
