#include "parser/line_reader.hpp"

#include <algorithm>
#include <cstring>

namespace twinpost {

std::size_t file_source::read(char* dst, std::size_t n) { return std::fread(dst, 1, n, file_); }

std::size_t string_source::read(char* dst, std::size_t n) {
  std::size_t k = std::min(n, text_.size());
  std::memcpy(dst, text_.data(), k);
  text_.remove_prefix(k);
  return k;
}

line_reader::line_reader(byte_source& src, std::size_t chunk) : src_(src), buf_(chunk < 16 ? 16 : chunk) {}

bool line_reader::fill() {
  if (eof_) return false;
  if (begin_ > 0) {
    std::memmove(buf_.data(), buf_.data() + begin_, end_ - begin_);
    end_ -= begin_;
    begin_ = 0;
  }
  if (end_ == buf_.size()) buf_.resize(buf_.size() * 2);  // a line longer than the buffer
  std::size_t n = src_.read(buf_.data() + end_, buf_.size() - end_);
  if (n == 0) eof_ = true;
  end_ += n;
  return n > 0;
}

std::string_view line_reader::peek(std::size_t n) {
  while (end_ - begin_ < n && fill()) {
  }
  return {buf_.data() + begin_, std::min(n, end_ - begin_)};
}

bool line_reader::next_physical(std::string_view& line) {
  std::size_t scanned = begin_;
  overlong_ = false;
  for (;;) {
    const char* base = buf_.data();
    const void* nl = std::memchr(base + scanned, '\n', end_ - scanned);
    if (nl) {
      std::size_t pos = static_cast<std::size_t>(static_cast<const char*>(nl) - base);
      line = {base + begin_, pos - begin_};
      consumed_ += pos + 1 - begin_;
      begin_ = pos + 1;
      if (line.size() > max_record_bytes) [[unlikely]] {
        overlong_head_.assign(line.substr(0, 256));
        overlong_ = true;
        line = overlong_head_;
      }
      break;
    }
    std::size_t had = end_ - begin_;
    if (had > max_record_bytes) [[unlikely]] {
      // No newline in sight: keep the start for the message, drop the rest unread.
      overlong_head_.assign(buf_.data() + begin_, 256);
      consumed_ += had;
      begin_ = end_;
      skip_rest_of_line();
      overlong_ = true;
      line = overlong_head_;
      ++line_no_;
      return true;
    }
    if (!fill()) {
      if (end_ == begin_) return false;
      line = {buf_.data() + begin_, end_ - begin_};  // last line without a newline
      consumed_ += end_ - begin_;
      begin_ = end_;
      break;
    }
    scanned = begin_ + had;
  }
  ++line_no_;
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  return true;
}

void line_reader::skip_rest_of_line() {
  for (;;) {
    const void* nl = std::memchr(buf_.data() + begin_, '\n', end_ - begin_);
    if (nl) {
      std::size_t pos = static_cast<std::size_t>(static_cast<const char*>(nl) - buf_.data());
      consumed_ += pos + 1 - begin_;
      begin_ = pos + 1;
      return;
    }
    consumed_ += end_ - begin_;
    begin_ = end_;
    if (!fill()) return;
  }
}

namespace {

bool blank(char c) { return c == ' ' || c == '\t'; }

// The data part of a physical line: [0, data_end), and whether it continues on the next.
struct line_shape {
  std::size_t data_end;
  bool continues;
};

line_shape shape_of(std::string_view line) {
  std::size_t first = 0;
  while (first < line.size() && blank(line[first])) ++first;
  std::string_view rest = line.substr(first);
  std::size_t end = line.size();
  if (rest.substr(0, 2) == "$$") {
    if (rest.substr(0, 4) != "$$->") return {line.size(), false};  // plain comment
  } else {
    // A trailing comment: the first "$$". memchr finds a '$' far faster than find("$$"),
    // and most lines have none at all.
    const char* base = line.data();
    const void* d = std::memchr(base + first, '$', line.size() - first);
    while (d) {
      std::size_t c = static_cast<std::size_t>(static_cast<const char*>(d) - base);
      if (c + 1 < line.size() && line[c + 1] == '$') {
        end = c;
        break;
      }
      d = c + 1 < line.size() ? std::memchr(base + c + 1, '$', line.size() - c - 1) : nullptr;
    }
  }
  std::size_t last = end;
  while (last > first && blank(line[last - 1])) --last;
  if (last > first + 1 && line[last - 1] == '$' && line[last - 2] != '$') return {last - 1, true};
  if (last == first + 1 && line[first] == '$') return {first, true};
  return {end, false};
}

bool all_blank(std::string_view s) {
  return std::all_of(s.begin(), s.end(), [](char c) { return blank(c); });
}

}  // namespace

bool line_reader::next(logical_record& out) {
  // Nearly every line of a job is whole in the buffer, starts with its data and has no '$'
  // (no comment, no continuation): the shape is then known without reading it again.
  if (const void* nl = std::memchr(buf_.data() + begin_, '\n', end_ - begin_)) {
    const char* base = buf_.data() + begin_;
    std::string_view line(base, static_cast<std::size_t>(static_cast<const char*>(nl) - base));
    const std::size_t taken = line.size() + 1;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (!line.empty() && !blank(line.front()) && line.size() <= max_record_bytes &&
        !std::memchr(line.data(), '$', line.size())) {
      consumed_ += taken;
      begin_ += taken;
      ++line_no_;
      overlong_ = false;
      segments_.clear();
      segments_.push_back({0, line_no_, 0, line});
      out.line = line_no_;
      out.problem = record_problem::none;
      out.text = line;
      return true;
    }
  }
  std::string_view line;
  line_shape shape{};
  do {
    if (!next_physical(line)) return false;
    shape = shape_of(line);
  } while (!overlong_ && all_blank(line.substr(0, shape.data_end)) && !shape.continues);

  segments_.clear();
  out.line = line_no_;
  out.problem = record_problem::none;
  if (overlong_) [[unlikely]] {
    segments_.push_back({0, line_no_, 0, line});
    out.text = line;
    out.problem = record_problem::too_long;
    out.problem_line = line_no_;
    out.problem_column = 1;
    out.problem_source = line;
    return true;
  }
  if (!shape.continues) {  // the common case: no copy at all
    segments_.push_back({0, line_no_, 0, line});
    out.text = line.substr(0, shape.data_end);
    return true;
  }
  // A continued record: copy its lines, since refilling the buffer moves them.
  joined_.clear();
  physical_.clear();
  spans_.clear();
  std::size_t used = 0;
  std::size_t kept = 0;  // bytes of the physical lines kept: bounded by max_record_bytes
  auto keep = [&](std::string_view physical, std::size_t data_end) {
    // One buffer for all the lines: memory follows the record's size, whatever the lines
    // of earlier records were.
    spans_.emplace_back(physical_.size(), physical.size());
    physical_.append(physical);
    segments_.push_back({joined_.size(), line_no_, 0, {}});
    joined_.append(physical.substr(0, data_end));
    kept += physical.size() + 1;
    ++used;
  };
  keep(line, shape.data_end);
  std::size_t dollar = shape.data_end;  // where the last kept line's continuation `$` is
  std::size_t problem_at = 0;           // the kept line the problem is on
  while (shape.continues) {
    if (!next_physical(line)) {
      // The input ends where the record says it goes on: the job is cut off.
      if (out.problem == record_problem::none) {
        out.problem = record_problem::dangling;
        out.problem_line = line_no_;
        out.problem_column = static_cast<int>(dollar) + 1;
        problem_at = used - 1;
      }
      break;
    }
    shape = shape_of(line);
    if (out.problem == record_problem::too_long || overlong_ || kept + line.size() + 1 > max_record_bytes)
        [[unlikely]] {
      // Too long as a whole: read on to its end, keep nothing more.
      if (out.problem == record_problem::none) {
        out.problem = record_problem::too_long;
        out.problem_line = line_no_;
        out.problem_column = 1;
        keep(line.substr(0, std::min<std::size_t>(line.size(), 256)), 0);
        problem_at = used - 1;
      }
      if (overlong_) break;  // its end went with the rest of the line
      continue;
    }
    dollar = shape.data_end;
    keep(line, shape.data_end);
  }
  // Views into physical_ stay valid: it is not touched until next().
  const std::string_view all = physical_;
  for (std::size_t i = 0; i < used; ++i)
    segments_[i].physical = all.substr(spans_[i].first, spans_[i].second);
  if (out.problem != record_problem::none) out.problem_source = segments_[problem_at].physical;
  out.text = joined_;
  return true;
}

source_position line_reader::locate(std::size_t offset) const {
  if (segments_.empty()) return {};
  auto it = std::upper_bound(segments_.begin(), segments_.end(), offset,
                             [](std::size_t o, const segment& s) { return o < s.offset; });
  const segment& s = it == segments_.begin() ? segments_.front() : *(it - 1);
  return {s.line, static_cast<int>(s.column0 + (offset - s.offset)) + 1, s.physical};
}

}  // namespace twinpost
