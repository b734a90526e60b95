#include "check/nc_program.hpp"
#include "machines/partner_list.hpp"
#include "support/ascii.hpp"
#include "support/errors.hpp"
#include "support/file_reader.hpp"

#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cstdint>

namespace twinpost {

namespace {

using ascii::is_blank;
using ascii::is_digit;
using ascii::is_letter;
using ascii::upper;

// Line ends in a run of text: a plain loop that the compiler turns into vector code.
int count_newlines(const char* p, std::size_t n) {
  int lines = 0;
  for (std::size_t i = 0; i < n; ++i) lines += p[i] == '\n';
  return lines;
}

bool all_digits(std::string_view s) { return !s.empty() && std::all_of(s.begin(), s.end(), is_digit); }

/// An unsigned integer value ("100", "03"); false for signs, points and expressions.

bool to_int(std::string_view s, int& out) {
  if (!all_digits(s)) return false;
  auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc() && end == s.data() + s.size();
}

/// Upper case, blanks and comments removed: how a marker line is compared.
std::string squeeze(std::string_view s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '(') {
      i = s.find(')', i);
      if (i == std::string_view::npos) break;
      continue;
    }
    if (s[i] == ';') break;
    if (!is_blank(s[i])) out += upper(s[i]);
  }
  return out;
}

/// A section marker template split around "{channel}".
struct marker_pattern {
  bool active = false;
  std::string prefix, suffix;
};

marker_pattern make_marker(std::string_view tpl) {
  constexpr std::string_view hole = "{channel}";
  const std::size_t at = tpl.find(hole);
  if (at == std::string_view::npos) return {};
  marker_pattern p{true, squeeze(tpl.substr(0, at)), squeeze(tpl.substr(at + hole.size()))};
  p.active = !p.prefix.empty();  // a bare number would make every numbered line a marker
  return p;
}

/// A line as squeeze() sees it, walked without copying: upper case, blanks and comments
/// skipped, nothing after ';'.
class squeezed {
 public:
  explicit squeezed(std::string_view s) : s_(s) { skip(); }
  bool done() const { return i_ >= s_.size(); }
  char peek() const { return upper(s_[i_]); }
  void next() {
    ++i_;
    skip();
  }

 private:
  void skip() {
    while (i_ < s_.size()) {
      const char c = s_[i_];
      if (is_blank(c)) {
        ++i_;
      } else if (c == '(') {
        const std::size_t close = s_.find(')', i_);
        i_ = close == std::string_view::npos ? s_.size() : close + 1;
      } else if (c == ';') {
        i_ = s_.size();
      } else {
        return;
      }
    }
  }
  std::string_view s_;
  std::size_t i_ = 0;
};

/// The channel a marker line opens, or -1 when `line` is no marker. Called for every line
/// of a merged program, so it walks the line in place and gives up at the first mismatch.
int marker_channel(const marker_pattern& mk, std::string_view line) {
  squeezed w(line);
  // A sequence number may precede the marker ("N10 G109 L1").
  if (mk.prefix[0] != 'N' && !w.done() && w.peek() == 'N') {
    squeezed after = w;
    after.next();
    if (!after.done() && is_digit(after.peek())) {
      w = after;
      while (!w.done() && is_digit(w.peek())) w.next();
    }
  }
  for (char c : mk.prefix) {
    if (w.done() || w.peek() != c) return -1;
    w.next();
  }
  int channel = 0, digits = 0;
  while (!w.done() && is_digit(w.peek())) {
    if (++digits > 4) return -1;
    channel = channel * 10 + (w.peek() - '0');
    w.next();
  }
  if (digits == 0) return -1;
  for (char c : mk.suffix) {
    if (w.done() || w.peek() != c) return -1;
    w.next();
  }
  return channel;
}

/// Turns NC files into channel programs; one per read_nc_programs call.
class reader {
 public:
  reader(const machine& m, diagnostic_sink& sink, nc_programs& out, const nc_read_options& options)
      : m_(m), sink_(sink), out_(out), options_(options), state_(out.channels.size()) {
    if (bang_) {
      wait_addr_ = m.waits.marker;
      partner_addr_ = bang_partner_address;
    }
    end_codes_ = {2, 30, 99};  // M02, M30, M99 end a program on every control
    for (const nc_word& w : split_nc_words(m.program.end_code)) {
      int code = 0;
      if (w.address == 'M' && to_int(w.value, code)) end_codes_.push_back(code);
    }
  }

  /// Reads a whole file as the program of `channel` (split layout).
  void read_split(const nc_source& f, int channel) {
    begin_split(f, channel);
    for_each_line(
        f, [&](int no, std::string_view line, bool plain) { read_line(f, no, line, channel, plain); },
        split_runs(channel));
    end_split(f, channel);
  }

  // Where a file read piece by piece is between two pieces.
  struct stream_state {
    std::string carry;  // the start of a line the last piece did not end
    int no = 0;         // lines handed on so far
    bool first = true, skip_lf = false;
    bool stopped = false;  // a line too long ended the reading
  };

  /// The next piece of `channel`'s file (split layout), as its writer produced it;
  /// `chunk.data()[chunk.size()]` is a NUL (the scans stop at it).
  void feed_split(const nc_source& f, int channel, stream_state& s, std::string_view chunk) {
    auto on_line = [&](int no, std::string_view line, bool plain) { read_line(f, no, line, channel, plain); };
    stream_chunk(f, s, chunk, on_line, split_runs(channel));
  }

  /// The end of `channel`'s file fed piece by piece.
  void end_split(const nc_source& f, int channel, stream_state& s) {
    auto on_line = [&](int no, std::string_view line, bool plain) { read_line(f, no, line, channel, plain); };
    if (!s.stopped) stream_end(s, on_line);
    end_split(f, channel);
  }

  /// Starts the program of `channel` (split layout), read from `f`.
  void begin_split(const nc_source& f, int channel) {
    out_.channels[static_cast<std::size_t>(channel - 1)].file = f.name;
  }

  // A split file read to its end: a channel with no block has no program.
  void end_split(const nc_source& f, int channel) {
    if (!state_[static_cast<std::size_t>(channel - 1)].has_block)
      report(severity::error, {f.name, 0, 0, {}},
             fmt::format("no NC block in this file: channel {} has no program", channel));
  }

  // Runs of plain blocks may be skipped: only the last of a run matters here, once the
  // channel is known to have a block at all (until then every line is looked at), unless
  // every block goes to on_block.
  const bool* split_runs(int channel) const {
    return options_.on_block ? nullptr : &state_[static_cast<std::size_t>(channel - 1)].has_block;
  }

  /// Reads a file with section markers (merged layouts).
  void read_sections(const nc_source& f) {
    for (nc_channel_program& p : out_.channels) p.file = f.name;
    const marker_pattern mk = make_marker(m_.program.section_marker);
    // `$n` sections (Citizen/Mitsubishi, twinpost's merged-sections layout) are read on any
    // machine as well: a line `$1` means nothing else in a program.
    const marker_pattern dollar = make_marker("${channel}");
    // Without any marker every wait would be "outside the sections": say the one thing.
    // One pass: the warnings about waits outside the sections wait until a marker is seen.
    bool any_marker = false, dollar_seen = false;
    const int mk_words = mk.active ? marker_words(m_.program.section_marker) : 0;
    deferred_.clear();
    deferring_ = true;
    int current = 0;  // 0: common blocks or a data section; -1: an unknown channel's section
    for_each_line(f, [&](int no, std::string_view line, bool plain) {
      int c = mk.active ? marker_channel(mk, line) : -1;
      const bool by_dollar = c < 0 && (c = marker_channel(dollar, line)) >= 0;
      dollar_seen = dollar_seen || by_dollar;
      if (c < 0) return read_line(f, no, line, current, plain);
      any_marker = true;
      current = c;
      if (c > static_cast<int>(out_.channels.size())) {
        std::string written = by_dollar ? "${channel}" : m_.program.section_marker;
        written.replace(written.find("{channel}"), 9, std::to_string(c));
        report(severity::error, {f.name, no, marker_column(line, mk), std::string(line)},
               fmt::format("section marker {} opens a section for channel {}, which this "
                           "machine does not have",
                           written, c));
        current = -1;
        return;
      }
      if (c > 0) {
        channel_state& st = state_[static_cast<std::size_t>(c - 1)];
        if (!st.has_section) st.marker = {f.name, no, marker_column(line, mk), std::string(line)};
        st.has_section = true;
      }
      // The marker block may carry more words (T0101): only those make it a block.
      read_line(f, no, line, current, false, by_dollar ? 0 : mk_words);
    });
    deferring_ = false;
    if (!any_marker) {
      deferred_.clear();
      if (!mk.active)
        report(severity::error, {f.name, 0, 0, {}},
               fmt::format("this machine has {} channels but one file was given, and its "
                           "programs have no section markers: give one file per channel",
                           out_.channels.size()));
      else
        report(severity::error, {f.name, 0, 0, {}},
               fmt::format("no section marker ({}) in this file: this machine has {} channels; "
                           "give one file per channel, or one file with sections",
                           m_.program.section_marker, out_.channels.size()));
      return;
    }
    for (diagnostic& d : deferred_) sink_.report(std::move(d));
    deferred_.clear();
    for (std::size_t i = 0; i < state_.size(); ++i) {
      if (state_[i].has_section && !state_[i].has_block)
        report(severity::error, state_[i].marker,
               fmt::format("no NC block in the section for channel {}: channel {} has no "
                           "program",
                           i + 1, i + 1));
      if (state_[i].has_section) continue;
      // Name the marker in the form the file uses: the machine's, or `$n`.
      std::string marker = mk.active && !dollar_seen ? m_.program.section_marker : "${channel}";
      marker.replace(marker.find("{channel}"), 9, std::to_string(i + 1));
      report(severity::error, {f.name, 0, 0, {}},
             fmt::format("no section for channel {} ({}) in this file", i + 1, marker));
    }
  }

  /// Settles where each channel's program ends.
  void finish() {
    for (std::size_t i = 0; i < state_.size(); ++i) {
      nc_channel_program& p = out_.channels[i];
      const channel_state& st = state_[i];
      if (!st.ended) p.end = {st.last_file, st.last_line, 0, st.last_text};
      if (p.end.file.empty()) p.end.file = p.file;
    }
  }

 private:
  struct channel_state {
    bool has_section = false;
    nc_place marker;         // the first marker line of the channel's sections
    bool has_block = false;  // a block with a word (not a marker, comment or '%')
    bool ended = false;
    // The last block read. A plain block is only noted as a view into the line buffer
    // (`pending`), and copied when the buffer moves on: most blocks are plain.
    std::string last_file;
    int last_line = 0;
    std::string last_text;
    const nc_source* pending_source = nullptr;
    std::string_view pending_text;
  };

  // Copies the plain blocks noted as views, before the lines they point into go away.
  void settle() {
    for (channel_state& st : state_) {
      if (!st.pending_source) continue;
      st.last_file = st.pending_source->name;
      st.last_text.assign(st.pending_text);
      st.pending_source = nullptr;
    }
  }
  std::vector<diagnostic> deferred_;  // outside-section warnings, until a marker is seen
  bool deferring_ = false;

  // Calls on_line for every line; lines are views that stay valid until settle() is called
  // (at the end of each chunk read from disk, and at the end).
  // `runs`: while *runs is true, a run of plain blocks may be handed on as its last block
  // alone (line numbers still count them all); for callers that look only at the last one.
  template <class F>
  void for_each_line(const nc_source& f, F&& on_line, const bool* runs = nullptr) {
    if (f.copy || !f.path.empty()) {
      stream_lines(f, on_line, runs);
      return;
    }
    std::string_view text = f.text;
    if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);  // UTF-8 byte order mark
    int no = 0;
    std::size_t pos = 0;
    while (pos < text.size()) {
      // Lines end in LF, CR LF or a lone CR (old controls' tapes).
      const std::size_t eol = std::min(line_end(text, pos), text.size());
      if (eol - pos > nc_max_line_bytes) return too_long(f, no + 1);
      const std::string_view line = text.substr(pos, eol - pos);
      pos = eol + 1;
      if (eol < text.size() && text[eol] == '\r' && pos < text.size() && text[pos] == '\n') ++pos;
      on_line(++no, line, false);
    }
    settle();
  }

  // A line past nc_max_line_bytes ends the reading of its file (memory stays bounded).
  void too_long(const nc_source& f, int no) {
    settle();  // the views noted so far still point into live text
    report(severity::error, {f.name, no, static_cast<int>(nc_max_line_bytes) + 1, {}},
           fmt::format("line {} is longer than {} bytes: no NC block is that long; the rest of "
                       "the file is not read",
                       no, nc_max_line_bytes));
  }

  // The first CR or LF at or after `pos` (memchr twice beats find_first_of on long text).
  static std::size_t line_end(std::string_view text, std::size_t pos) {
    const char* base = text.data();
    const void* lf = std::memchr(base + pos, '\n', text.size() - pos);
    std::size_t end = lf ? static_cast<std::size_t>(static_cast<const char*>(lf) - base) : text.size();
    const void* cr = std::memchr(base + pos, '\r', end - pos);
    if (cr) return static_cast<std::size_t>(static_cast<const char*>(cr) - base);
    return lf ? end : std::string_view::npos;
  }

  // From `pos` in a NUL-terminated chunk: every whole line before the next special
  // character or CR is a plain block (or blank). Counts them with no call per line, hands on
  // the last one that is not blank (blank lines hold nothing), and moves `pos` and `no`
  // past them. False when there is no such line at `pos`.
  template <class F>
  bool consume_run(std::string_view chunk, std::size_t& pos, int& no, F& on_line) {
    const char* base = chunk.data();
    const std::size_t stop = pos + span_until(base + pos, run_stops_);
    const void* nl = stop > pos ? memrchr(base + pos, '\n', stop - pos) : nullptr;
    if (!nl) return false;
    const std::size_t end = static_cast<std::size_t>(static_cast<const char*>(nl) - base);
    const int total = count_newlines(base + pos, end + 1 - pos);
    // Walking back over blank lines visits each once: they are consumed with the run.
    std::size_t line_end = end;
    int after = 0;  // lines of the run after the one handed on
    for (;;) {
      const void* before = line_end > pos ? memrchr(base + pos, '\n', line_end - pos) : nullptr;
      const std::size_t start =
          before ? static_cast<std::size_t>(static_cast<const char*>(before) - base) + 1 : pos;
      const std::string_view line = chunk.substr(start, line_end - start);
      if (line.find_first_not_of(" \t") != std::string_view::npos) {
        on_line(no + total - after, line, true);
        break;
      }
      if (!before) break;  // all blank
      line_end = start - 1;
      ++after;
    }
    no += total;
    pos = end + 1;
    return true;
  }

  // The same lines as above, read from a file a megabyte at a time. Most lines are plain
  // blocks: one scan to the first stop character (the special ones, CR and LF; a table
  // look-up per byte) finds the end of such a line and says it is plain in the same pass.
  // Every line is settled before it returns: the last one may live in `carry`.
  template <class F>
  void stream_lines(const nc_source& f, F&& on_line, const bool* runs) {
    file_ptr own(nullptr, &std::fclose);
    std::FILE* file = f.copy.get();
    if (file) {
      std::rewind(file);
    } else {
      own = open_file_ptr(f.path.c_str(), "rb");
      file = own.get();
    }
    if (!file) throw config_error(fmt::format("cannot read '{}'", f.path));
    chunk_reader reader(file);  // each chunk ends in the NUL the scans stop at
    stream_state s;
    for (std::string_view chunk; !(chunk = reader.next()).empty();) {
      stream_chunk(f, s, chunk, on_line, runs);
      if (s.stopped) return;
    }
    // A read error (EIO, a directory) must not pass for the end of the program.
    if (reader.failed())
      throw config_error(fmt::format("cannot read '{}': {}", f.path, std::strerror(errno)));
    stream_end(s, on_line);
  }

  // One piece of a streamed file (NUL after its end): its whole lines handed on, the start
  // of a line it does not end kept in s.carry. Every line is settled before it returns.
  template <class F>
  void stream_chunk(const nc_source& f, stream_state& s, std::string_view chunk, F& on_line,
                    const bool* runs) {
    if (s.stopped) return;
    // A byte order mark is taken off whole from the first piece (pieces are 1 MB read from a
    // file, 64 KB from a writer, which writes none).
    if (s.first && chunk.starts_with("\xEF\xBB\xBF")) chunk.remove_prefix(3);
    s.first = false;
    std::string& carry = s.carry;
    int& no = s.no;
    std::size_t pos = 0;
    if (s.skip_lf && !chunk.empty() && chunk[0] == '\n') pos = 1;  // CR LF split by the chunk
    s.skip_lf = false;
    while (pos < chunk.size()) {
      if (runs && *runs && carry.empty() && consume_run(chunk, pos, no, on_line)) continue;
      if (carry.empty() && !is_blank(chunk[pos])) {
        // A line that reaches its LF with no stop character on the way, and does not start
        // blank, is a plain block (an embedded NUL stops the scan too: the slow way then).
        const std::size_t len = span_until(chunk.data() + pos, stops_);
        if (len > 0 && chunk.data()[pos + len] == '\n') {
          on_line(++no, chunk.substr(pos, len), true);
          pos += len + 1;
          continue;
        }
      }
      std::size_t eol = line_end(chunk, pos);
      const std::size_t len = (eol == std::string_view::npos ? chunk.size() : eol) - pos;
      if (carry.size() + len > nc_max_line_bytes) {
        s.stopped = true;
        return too_long(f, no + 1);
      }
      if (eol == std::string_view::npos) {
        carry.append(chunk.substr(pos));
        break;
      }
      std::string_view line = chunk.substr(pos, eol - pos);
      const bool carried = !carry.empty();
      if (carried) {
        carry.append(line);
        line = carry;
      }
      on_line(++no, line, false);
      if (carried) settle();  // the line lives in `carry`, cleared now
      carry.clear();
      pos = eol + 1;
      if (chunk[eol] == '\r') {
        if (pos < chunk.size() && chunk[pos] == '\n')
          ++pos;
        else if (pos == chunk.size())
          s.skip_lf = true;
      }
    }
    settle();  // the buffer is read over next
  }

  // The end of a streamed file: a last line without a line end.
  template <class F>
  void stream_end(stream_state& s, F& on_line) {
    if (s.carry.empty()) return;
    on_line(++s.no, s.carry, false);
    settle();  // before `carry` goes
  }

  void report(severity level, nc_place at, std::string message) {
    if (deferring_ && level == severity::warning) {
      deferred_.push_back(
          {level, std::move(at.file), at.line, at.column, std::move(message), std::move(at.source_line)});
      return;
    }
    sink_.report(
        {level, std::move(at.file), at.line, at.column, std::move(message), std::move(at.source_line)});
  }

  // Where a line is, for the places of what it holds.
  struct line_place {
    const nc_source& f;
    int no;
    std::string_view line;
    nc_place operator()(int column) const { return {f.name, no, column, std::string(line)}; }
  };

  std::string name(const nc_word& w) const {
    if (bang_ && w.address == wait_addr_) {
      for (const auto& [column, text] : bang_text_)
        if (column == w.column) return text;
    }
    return fmt::format("{}{}", w.address, w.value);
  }

  // The address given to the partners of a bang wait (`2` of `!2L1`): no letter, so that
  // no word of the program can be taken for it.
  static constexpr char bang_partner_address = '\x01';

  // Bang syntax (Citizen/Mitsubishi `!2L1`, `!23L5`, `!2!3L5`): each wait in `line` becomes
  // two words, the wait (address waits.marker, value the number, column of the marker) and
  // its partners (as written between the marker and the number's address), in place of the
  // number's word that split_nc_words made of `L1`. A marker without a number is an error.
  void read_bang_waits(std::string_view line, std::vector<nc_word>& words, int channel,
                       const line_place& at) {
    bang_text_.clear();
    const char marker = m_.waits.marker;
    for (std::size_t i = 0; i < line.size(); ++i) {
      const char c = line[i];
      if (c == '(') {
        const std::size_t close = line.find(')', i);
        if (close == std::string_view::npos) return;
        i = close;
        continue;
      }
      if (c == ';') return;
      if (c != marker) continue;
      const std::size_t start = i;
      std::size_t j = i + 1;
      for (;;) {
        while (j < line.size() && is_digit(line[j])) ++j;
        if (j < line.size() && line[j] == marker && j + 1 < line.size() && is_digit(line[j + 1])) {
          ++j;
          continue;
        }
        break;
      }
      const std::string_view partners = line.substr(i + 1, j - (i + 1));  // as written, in the line
      std::size_t k = j;
      while (k < line.size() && is_blank(line[k])) ++k;
      const int start_column = static_cast<int>(start) + 1;
      auto number = std::find_if(words.begin(), words.end(),
                                 [&](const nc_word& w) { return w.column == static_cast<int>(k) + 1; });
      if (k >= line.size() || upper(line[k]) != m_.waits.address || number == words.end()) {
        if (channel >= 0)
          report(
              severity::error, at(start_column),
              fmt::format("'{}' is no wait: a wait is {}<partners>{}<number>, e.g. {}2{}1",
                          line.substr(start, j - start), marker, m_.waits.address, marker, m_.waits.address));
        i = j - 1;
        continue;
      }
      nc_word wait = *number;
      wait.address = marker;
      wait.column = start_column;
      std::size_t end = k + 1;  // past the number, as split_nc_words read it
      while (end < line.size() && is_blank(line[end])) ++end;
      end = std::min(end + number->value.size(), line.size());
      bang_text_.emplace_back(start_column, std::string(line.substr(start, end - start)));
      *number = wait;
      words.push_back({partner_addr_, partners, false, start_column + 1});
      i = end - 1;
    }
  }

  /// An M-code that is no wait but may have been meant as one (the checker judges).
  bool looks_like_wait(int code, const nc_word* partner, bool has_g) const {
    const wait_rules& wr = m_.waits;
    if (std::find(wr.excluded.begin(), wr.excluded.end(), code) != wr.excluded.end()) return false;
    if (code >= wr.first && code <= wr.last) return true;  // in the range, off its step
    // M98/M198 P calls a subprogram, and with a G-code the P is the G-code's (G04 P).
    return partner && !has_g && code != 98 && code != 198;
  }

  nc_wait make_wait(int channel, int code, const nc_word* partner, nc_place at) const {
    nc_wait w;
    w.channel = channel;
    w.code = code;
    if (partner) {
      w.has_partner_list = true;
      w.partner_text = partner->value;
      std::string digits(partner->value);  // bang: `2!3` lists channels 2 and 3
      if (bang_) std::erase(digits, m_.waits.marker);
      w.partners_readable =
          !partner->expression && decode_partner_list(digits, m_.waits.partners, w.partners);
      w.partner_column = partner->column;
    }
    w.where = std::move(at);
    return w;
  }

  // `channel`: 1..n a channel, 0 common blocks or data, -1 an unknown channel's section.
  // `plain`: the caller knows the line is a plain block (see plain_block).
  // `marker_words`: -1 for a line that is no section marker, else the number of words of
  // the marker itself (G109 L1: 2; $1: 0), which do not make the line a block.
  void read_line(const nc_source& f, int no, std::string_view line, int channel, bool plain,
                 int marker_words = -1) {
    if (channel > 0) note_block(state_[static_cast<std::size_t>(channel - 1)], line, marker_words);
    if (channel > 0 && (plain || plain_block(line)))
      return note_plain_block(f, no, line, channel,
                              marker_words < 0 || block_beyond_marker(split_nc_words(line), marker_words));
    letters_ = split_nc_words(line, words_);
    std::vector<nc_word>& words = words_;
    const line_place at{f, no, line};
    if (bang_) {
      read_bang_waits(line, words, channel, at);
      letters_ &= nc_variable_bit;  // (the split's: the bang waits' words are its own)
      for (const nc_word& w : words) letters_ |= nc_letter(w.address);
    }
    if (channel >= 0 && !(channel > 0 && state_[static_cast<std::size_t>(channel - 1)].ended))
      report_jumps(line, words, at);
    if (words.empty()) {
      if (options_.on_macro && channel > 0 && !state_[static_cast<std::size_t>(channel - 1)].ended &&
          line.find('#') != std::string_view::npos) {
        const nc_block blk(channel, f.name, no, line, words_, letters_);
        if (options_.before_block) options_.before_block(blk);
        options_.on_macro(blk);
      }
      return;
    }
    const block_words b = classify_words(words, channel, at);
    if (channel < 0) return;
    if (channel == 0) {
      if (b.wait)
        report(severity::warning, at(b.wait->column),
               fmt::format("wait {} lies outside every channel's section and is not checked", name(*b.wait)));
      return;
    }
    record_block(b, channel, at, marker_words < 0 || block_beyond_marker(words, marker_words));
  }

  // Jumps, loops and calls the checker does not follow: it reads each program once, top to
  // bottom, so a wait behind one may run more often, or not at all, or live in a program it
  // never reads. Said as a warning at the word, never passed over.
  void report_jumps(std::string_view line, const std::vector<nc_word>& words, const line_place& at) {
    int if_column = 0;
    for (std::size_t i = 0; i < line.size();) {
      const char c = line[i];
      if (c == '(') {
        const std::size_t close = line.find(')', i);
        if (close == std::string_view::npos) break;
        i = close + 1;
        continue;
      }
      if (c == ';') break;
      if (!is_letter(c)) {
        ++i;
        continue;
      }
      std::size_t j = i;
      std::string key;
      while (j < line.size() && is_letter(line[j])) key += upper(line[j++]);
      const int column = static_cast<int>(i) + 1;
      if (key == "GOTO")
        report(
            severity::warning, at(column),
            "GOTO: the checker does not follow jumps; the waits are checked in the order they are written");
      else if (key == "WHILE")
        report(severity::warning, at(column),
               "WHILE loop: the checker reads its blocks once; waits in it are checked as if it ran once");
      else if (key == "IF")
        if_column = column;
      else if (key.starts_with("THEN") && if_column > 0 &&
               !words.empty())  // (attack 67 M9: `.. THEN M5`, then M69;
                                // an alarm `.. THEN #3000=1` moves nothing)
        report(
            severity::warning, at(if_column),
            "IF ... THEN: the checker does not evaluate the condition; the codes after THEN are checked as "
            "if it held (a stop there counts as a stop, a wait as a wait)");
      i = j;
    }
    for (const nc_word& w : words) {
      if (!w.numeric) continue;
      const double v = w.number;
      const bool call = w.address == 'M' && (v == 98 || v == 198);
      const bool macro = w.address == 'G' && (v == 65 || v == 66 || v == 66.1);
      if (!call && !macro) continue;  // most words: nothing to format
      const std::string code = fmt::format("{}{}", w.address, w.value);
      const nc_word* program = nullptr;
      for (const nc_word& p : words)
        if (p.address == 'P' && !program) program = &p;
      const std::string called = program ? fmt::format(" P{}", program->value) : std::string();
      if (call)
        report(severity::warning, at(w.column),
               fmt::format("{}{} calls a subprogram the checker does not read: waits in it are not checked",
                           code, called));
      else
        report(severity::warning, at(w.column),
               fmt::format("{}{} calls a macro the checker does not read: waits in it are not checked", code,
                           called));
    }
  }

  // A marker line that carries more than the marker's own words (and an N number).
  static bool block_beyond_marker(const std::vector<nc_word>& words, int marker_words) {
    int n = 0;
    for (const nc_word& w : words) n += w.address != 'N';
    return n > marker_words;
  }

  // The words of one block that matter to the checker.
  struct block_words {
    const nc_word* partner = nullptr;  // the first partner-list word (P on Fanuc)
    bool has_g = false;
    const nc_word* wait = nullptr;  // the first wait code, and its number
    int wait_code = 0;
    const nc_word* end = nullptr;                      // the first end-of-program M-code
    std::vector<std::pair<const nc_word*, int>> near;  // codes that may be meant as waits
  };

  // A block with no M-word, comment or special character holds no wait and no end: only
  // remember it as the channel's last block. Most of a program is such blocks.
  void note_plain_block(const nc_source& f, int no, std::string_view line, int channel,
                        bool is_block = true) {
    channel_state& st = state_[static_cast<std::size_t>(channel - 1)];
    if (st.ended) return;
    st.last_line = no;
    st.pending_source = &f;
    st.pending_text = line;
    if (options_.on_block && is_block) {
      const nc_block blk(channel, f.name, no, line, words_);
      if (options_.before_block) options_.before_block(blk);
      options_.on_block(blk);
    }
  }

  // Whether a '/' (block delete, /1../9) stands before column `column` (1-based) of `line`,
  // outside comments: the control skips what follows it when the switch is on.
  static bool under_block_delete(std::string_view line, int column) {
    const std::size_t end = std::min(line.size(), static_cast<std::size_t>(std::max(column - 1, 0)));
    for (std::size_t i = 0; i < end; ++i) {
      if (line[i] == '(') {
        const std::size_t close = line.find(')', i);
        if (close == std::string_view::npos) return false;
        i = close;
      } else if (line[i] == ';') {
        return false;
      } else if (line[i] == '/') {
        return true;
      }
    }
    return false;
  }

  // Sorts the words of a block into wait, end and near-waits; a wait given as an expression
  // and a second wait in the block are reported here (not in an unknown channel's section).
  block_words classify_words(const std::vector<nc_word>& words, int channel, const line_place& at) {
    const wait_rules& wr = m_.waits;
    block_words b;
    for (const nc_word& w : words) {
      if (w.address == partner_addr_ && !b.partner) b.partner = &w;
      b.has_g = b.has_g || w.address == 'G';
    }
    for (const nc_word& w : words) {
      if (w.address == wait_addr_ && w.expression && channel >= 0) {
        report(severity::warning, at(w.column),
               fmt::format("{} is a variable or expression: a wait given so cannot be checked", name(w)));
        continue;
      }
      int code = 0;
      if (!to_int(w.value, code)) continue;
      if (w.address == wait_addr_ && wr.is_any_wait(code)) {
        if (channel >= 0 && under_block_delete(at.line, w.column))
          report(severity::error, at(w.column),
                 fmt::format("wait {} is under block delete ('/'): with the block delete switch on the "
                             "control skips it, and the channels wait for ever or lose this sync point",
                             name(w)));
        if (!b.wait) {
          b.wait = &w;
          b.wait_code = code;
        } else if (channel >= 0) {
          report(severity::error, at(w.column),
                 fmt::format("two waits in one block ({} and {}): a wait needs a block of its "
                             "own",
                             name(*b.wait), name(w)));
        }
      } else if (w.address == 'M' &&
                 std::find(end_codes_.begin(), end_codes_.end(), code) != end_codes_.end()) {
        if (!b.end) b.end = &w;
      } else if (w.address == wait_addr_ && looks_like_wait(code, b.partner, b.has_g)) {
        b.near.emplace_back(&w, code);
      }
    }
    return b;
  }

  // A block of channel `channel` (1..n) with words: the channel's last block, and its wait,
  // near-waits and end, unless the channel's program has already ended.
  // `is_block`: false for a section marker line with nothing else (not handed to on_block).
  void record_block(const block_words& b, int channel, const line_place& at, bool is_block) {
    channel_state& st = state_[static_cast<std::size_t>(channel - 1)];
    nc_channel_program& prog = out_.channels[static_cast<std::size_t>(channel - 1)];
    if (st.ended) {
      if (b.wait)
        report(severity::warning, at(b.wait->column),
               fmt::format("wait {} comes after the end of channel {}'s program at {}:{} and "
                           "is not checked",
                           name(*b.wait), channel, prog.end.file, prog.end.line));
      return;
    }
    st.pending_source = nullptr;
    if (st.last_file != at.f.name) st.last_file = at.f.name;
    st.last_line = at.no;
    st.last_text.assign(at.line);
    if (options_.on_block && is_block) {
      const nc_block blk(channel, at.f.name, at.no, at.line, words_, letters_);  // split in read_line
      if (options_.before_block) options_.before_block(blk);
      options_.on_block(blk);
    }
    if (b.wait) {
      nc_wait w = make_wait(channel, b.wait_code, b.partner, at(b.wait->column));
      if (options_.on_wait)
        options_.on_wait(w);
      else
        prog.waits.push_back(std::move(w));
    }
    for (const auto& [w, code] : b.near)
      prog.near_waits.push_back(make_wait(channel, code, b.partner, at(w->column)));
    if (b.end) {
      st.ended = true;
      prog.end = at(b.end->column);
    }
  }

  // Until a channel has a block, each of its lines is looked at for a word (a line of only
  // comments, '%' or blanks is none; nor are a section marker's own words, or N numbers).
  static void note_block(channel_state& st, std::string_view line, int marker_words) {
    if (st.has_block) return;
    int words = 0;
    for (const nc_word& w : split_nc_words(line)) words += marker_words < 0 || w.address != 'N';
    st.has_block = words > std::max(marker_words, 0);
  }

  // The column where a marker starts in its line: after blanks and a sequence number.
  static int marker_column(std::string_view line, const marker_pattern& mk) {
    std::size_t i = line.find_first_not_of(" \t");
    if (i == std::string_view::npos) return 1;
    if ((line[i] == 'N' || line[i] == 'n') && !(mk.active && mk.prefix[0] == 'N') && i + 1 < line.size() &&
        is_digit(line[i + 1])) {
      for (++i; i < line.size() && is_digit(line[i]);) ++i;
      i = std::min(line.find_first_not_of(" \t", i), line.size() - 1);
    }
    return static_cast<int>(i) + 1;
  }

  // How many words a section marker template has of its own ("G109 L{channel}": 2).
  static int marker_words(std::string marker) {
    const std::size_t hole = marker.find("{channel}");
    if (hole != std::string::npos) marker.replace(hole, 9, "1");
    int words = 0;
    for (const nc_word& w : split_nc_words(marker)) words += w.address != 'N';
    return words;
  }

  // True for a non-blank line that can hold neither a wait nor an end code nor anything
  // split_nc_words treats specially (comments, block delete, variables, '%').
  bool plain_block(std::string_view line) const {
    bool any = false;
    for (char c : line) {
      if (special_[static_cast<unsigned char>(c)]) return false;
      any = any || !is_blank(c);
    }
    return any;
  }

  // The characters that make a block worth a full look (see plain_block).
  static std::array<bool, 256> special_chars(char wait_address, const wait_rules& wr) {
    std::array<bool, 256> t{};
    if (wr.syntax == wait_syntax::bang) t[static_cast<unsigned char>(wr.marker)] = true;
    const char wa = upper(wait_address);
    // O and E (GOTO, DO, END) and P (M98 P, G65 P) bring the lines of jumps and calls.
    for (char c : {'M', 'm', wa, static_cast<char>(wa - 'A' + 'a'), '(', ';', '/', '#', '[', '%', '$', 'O',
                   'o', 'E', 'e', 'P', 'p'})
      t[static_cast<unsigned char>(c)] = true;
    return t;
  }

  // Where a scan for the end of a plain block stops in stream_lines: the special characters,
  // CR, LF (unless `lf` is false: a run of lines goes on past it) and the NUL that ends each
  // chunk. A table, not strcspn: glibc's fast strcspn takes at most 16 characters, and this
  // set has about 20 (its generic path rebuilds a table on every call).
  static std::array<bool, 256> stop_table(const std::array<bool, 256>& special, bool lf) {
    std::array<bool, 256> t = special;
    t['\0'] = t['\r'] = true;
    t['\n'] = lf;
    return t;
  }

  // The length of the span at `p` before the first byte of `stops` (a NUL is one).
  static std::size_t span_until(const char* p, const std::array<bool, 256>& stops) {
    const char* q = p;
    while (!stops[static_cast<unsigned char>(*q)]) ++q;
    return static_cast<std::size_t>(q - p);
  }

  const machine& m_;
  diagnostic_sink& sink_;
  nc_programs& out_;
  const nc_read_options& options_;
  const bool bang_ = m_.waits.syntax == wait_syntax::bang;
  char wait_addr_ = m_.waits.address;                   // the address of a wait's word (bang: the marker)
  char partner_addr_ = m_.waits.partner_address;        // the address of its partners
  std::vector<std::pair<int, std::string>> bang_text_;  // bang waits of the line: column, as written
  std::array<bool, 256> special_ = special_chars(m_.waits.address, m_.waits);
  std::array<bool, 256> stops_ = stop_table(special_, true);
  std::array<bool, 256> run_stops_ = stop_table(special_, false);  // a run of lines ends at CR or a special
  std::vector<channel_state> state_;
  std::vector<int> end_codes_;
  std::vector<nc_word> words_;  // the words of the line being read, split once (reused)
  std::uint32_t letters_ = 0;   // their addresses (nc_letter bits)
};

}  // namespace

nc_programs read_nc_programs(const std::vector<nc_source>& files, const machine& m, diagnostic_sink& sink,
                             const nc_read_options& options) {
  nc_programs out;
  for (std::size_t i = 0; i < m.channels.size(); ++i)
    out.channels.push_back({static_cast<int>(i) + 1, {}, {}, {}, {}});
  reader r(m, sink, out, options);
  if (files.empty()) {
    sink.report({severity::error, {}, 0, 0, "no NC files given", {}});  // no place: the run's
  } else if (files.size() == out.channels.size()) {
    for (std::size_t i = 0; i < files.size(); ++i) r.read_split(files[i], static_cast<int>(i) + 1);
  } else if (files.size() == 1) {
    r.read_sections(files[0]);
  } else {
    sink.report({severity::error,
                 files[0].name,
                 0,
                 0,
                 fmt::format("this machine has {} channels but {} files were given: give one "
                             "file per channel, or one file with sections",
                             m.channels.size(), files.size()),
                 {}});
  }
  r.finish();
  return out;
}

struct nc_stream_reader::impl {
  impl(const machine& m, diagnostic_sink& sink, const nc_read_options& options)
      : options(options), out(empty_programs(m)), sources(m.channels.size()), states(m.channels.size()),
        r(m, sink, out, this->options) {}

  static nc_programs empty_programs(const machine& m) {
    nc_programs p;
    for (std::size_t i = 0; i < m.channels.size(); ++i)
      p.channels.push_back({static_cast<int>(i) + 1, {}, {}, {}, {}});
    return p;
  }

  nc_read_options options;  // a copy: the reader keeps a reference
  nc_programs out;
  std::vector<nc_source> sources;  // by channel: the names (their addresses stay put)
  std::vector<reader::stream_state> states;
  std::vector<char> opened = std::vector<char>(sources.size(), 0);
  reader r;
};

nc_stream_reader::nc_stream_reader(const machine& m, diagnostic_sink& sink, const nc_read_options& options)
    : p_(std::make_unique<impl>(m, sink, options)) {}

nc_stream_reader::~nc_stream_reader() = default;

void nc_stream_reader::open(int channel, std::string name) {
  const auto i = static_cast<std::size_t>(channel - 1);
  p_->sources[i].name = std::move(name);
  p_->opened[i] = 1;
  p_->r.begin_split(p_->sources[i], channel);
}

void nc_stream_reader::feed(int channel, std::string_view chunk) {
  const auto i = static_cast<std::size_t>(channel - 1);
  p_->r.feed_split(p_->sources[i], channel, p_->states[i], chunk);
}

nc_programs nc_stream_reader::finish() {
  for (std::size_t i = 0; i < p_->sources.size(); ++i)
    if (p_->opened[i]) p_->r.end_split(p_->sources[i], static_cast<int>(i) + 1, p_->states[i]);
  p_->r.finish();
  return std::move(p_->out);
}

}  // namespace twinpost
