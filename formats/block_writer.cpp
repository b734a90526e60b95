#include "formats/block_writer.hpp"
#include "support/ascii.hpp"
#include "support/errors.hpp"

#include <cerrno>
#include <cstring>
#include <fmt/format.h>
#include <stdexcept>

namespace twinpost {

namespace {
// A full buffer goes to the file, or to the check while writing (relay): 64 KB, so that the
// check starts early and has little left when the writer ends (docs/benchmark.md, "Issue 23,
// sixth pass": the two-turret lathe job 2.5-4 % faster than with 256 KB).
constexpr std::size_t flush_at = 1 << 16;
}  // namespace

block_writer::block_writer(const std::string& path, const program_format& fmt, framing frame,
                           const word_format& n)
    : frame_(std::move(frame)), path_(path), fmt_(fmt), seq_(fmt, n) {
  f_ = std::fopen(path.c_str(), "wb");
  if (!f_) throw config_error(fmt::format("cannot write '{}': {}", path, std::strerror(errno)));
  // Every write is a whole buffer of ours: straight to the file, one system call each (through
  // stdio's 4 KB buffer a 64 KB piece took two).
  std::setvbuf(f_, nullptr, _IONBF, 0);
  buf_.reserve(flush_at + 4096);
}

block_writer::~block_writer() {
  // Not closed (a post that failed): a relay has written every piece by now (its owner stops
  // it before the writers go: post/post_job.cpp), so the file is not written after this.
  if (f_) std::fclose(f_);
}

void block_writer::start() {
  started_ = true;
  if (frame_.head) {
    head_ = frame_.head(seq_);
    buf_.append(head_);
  }
}

void block_writer::flush_if_full() {
  if (buf_.size() >= flush_at) {
    if (relay_) return pass_on();
    if (std::fwrite(buf_.data(), 1, buf_.size(), f_) != buf_.size()) write_failed(errno);
    out_bytes_ += buf_.size();
    buf_.clear();
  }
}

void block_writer::pass_on() {
  // A write that failed is said at the next piece, as a write of our own would have said it.
  if (const int err = relay_->write_error(false)) write_failed(err);
  out_bytes_ += buf_.size();
  *buf_.room(1) = '\0';  // the reader's scans stop at it; not one of the file's bytes
  buf_ = relay_->pass(std::move(buf_), f_);
  buf_.clear();
  buf_.reserve(flush_at + 4096);
}

void block_writer::pass_now() {
  if (started_ && relay_ && buf_.size() > 0) pass_on();  // (not started: nothing written, no name yet)
}

void block_writer::put(std::string_view s) {
  if (!started_) [[unlikely]]
    start();
  buf_.append(s);
  if (hook_) hook_(s);
  buf_ += '\n';
  flush_if_full();
}

text_buffer& block_writer::open_block() {
  if (!started_) [[unlikely]]
    start();
  open_at_ = buf_.size();
  return buf_;
}

void block_writer::end_block() {
  if (filter_ && !filtering_) [[unlikely]] {
    const std::string b(buf_.data() + open_at_, buf_.size() - open_at_);
    buf_.truncate(open_at_);
    return filtered(b, false);
  }
  ++blocks_;
  if (fmt_.sequence_start > 0) {
    const std::string n = seq_.next();
    if (!n.empty()) buf_.insert(open_at_, n);
  }
  if (hook_) hook_(std::string_view(buf_.data() + open_at_, buf_.size() - open_at_));
  buf_ += '\n';
  flush_if_full();
}

void block_writer::filtered(std::string_view words, bool restart) {
  filtering_ = true;
  std::string replacement;
  verdict v;
  try {
    v = filter_->filter(words, replacement);
  } catch (...) {
    filtering_ = false;
    throw;
  }
  if (v != verdict::drop) {
    const std::string_view out = v == verdict::replace ? std::string_view(replacement) : words;
    block(out, restart);
    try {
      filter_->block_written(out, v == verdict::replace);
    } catch (...) {
      filtering_ = false;
      throw;
    }
  }
  filtering_ = false;
}

void block_writer::block(std::string_view words, bool restart) {
  if (!started_) [[unlikely]]
    start();  // the head's blocks take the first numbers, and the filter sees them first
  if (filter_ && !filtering_) [[unlikely]]
    return filtered(words, restart);
  ++blocks_;
  if (fmt_.sequence_start > 0) {
    std::string line = seq_.next(restart);
    if (!line.empty()) {
      line.append(words);
      put(line);
      return;
    }
  }
  put(words);
}

void block_writer::comment(std::string_view text) {
  std::string s;
  s += fmt_.comment_open;
  s += safe_comment_text(text, fmt_);
  if (fmt_.comment_close != '\n') s += fmt_.comment_close;  // '\n': to the end of the line
  put(s);
}

void block_writer::raw(std::string_view line) { put(line); }

void block_writer::close() {
  if (!f_) return;
  if (!started_) start();
  if (frame_.tail) buf_.append(frame_.tail(seq_));
  const std::size_t last = buf_.size();
  bool ok = true;
  int err = 0;
  if (relay_) {
    // The last piece (even an empty one: the reader learns the program ends), then every
    // piece written before the file is closed.
    *buf_.room(1) = '\0';
    buf_ = relay_->pass(std::move(buf_), f_);
    err = relay_->write_error(true);
    ok = err == 0;
  } else {
    ok = std::fwrite(buf_.data(), 1, buf_.size(), f_) == buf_.size();
    err = ok ? 0 : errno;
  }
  out_bytes_ += last;
  buf_.clear();
  if (std::fclose(f_) != 0 && ok) {
    ok = false;
    err = errno;
  }
  f_ = nullptr;
  if (!ok) write_failed(err);
}

void block_writer::write_failed(int err) const {
  const std::string shown = frame_.name ? frame_.name() : path_;
  throw config_error(fmt::format("cannot write '{}': {}", shown, std::strerror(err)));
}

std::string safe_comment_text(std::string_view text, const program_format& fmt) {
  std::string s;
  for (unsigned char c : text) {
    c = static_cast<unsigned char>(ascii::upper(static_cast<char>(c)));
    if (c == static_cast<unsigned char>(fmt.comment_open) ||
        c == static_cast<unsigned char>(fmt.comment_close) || c == '(' || c == ')' || c == ';' || c == '%')
      c = ' ';
    if (c < 0x20 || c >= 0x7f) c = ' ';  // control bytes and ISO-8859-1 letters
    s += static_cast<char>(c);
  }
  while (!s.empty() && s.back() == ' ') s.pop_back();
  while (!s.empty() && s.front() == ' ') s.erase(s.begin());
  if (fmt.comment_max > 0 && static_cast<int>(s.size()) > fmt.comment_max)
    s.resize(static_cast<std::size_t>(fmt.comment_max));
  return s;
}

}  // namespace twinpost
