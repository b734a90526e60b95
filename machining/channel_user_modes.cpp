// The modal codes a user's [events] blocks may leave behind (issue 37, item 4): a block such as
// `G0 G18 G40 G80 G99` after a tool change puts the control in feed per revolution, and the
// post's next `F150.` for a drill fed per minute would be read as 150 mm/rev. After the user's
// blocks of one event the channel's own modes go back on: its feed mode, its plane, absolute
// positions. A block in the other unit system (G20 in a metric program) is refused: every
// later word would be read in it.
#include <fmt/format.h>

#include "machining/channel_writer.hpp"
#include "support/ascii.hpp"

namespace twinpost {

namespace {

// Whether `block` has the G word `code` ("G99", "G95", "G17"): a G at the start or after a
// non-letter, its number equal (G17 is not G170, G54 not G54.1), outside `(...)` comments.
bool has_g_code(std::string_view block, std::string_view code) {
  if (code.size() < 2 || code[0] != 'G') return false;
  const std::string_view number = code.substr(1);
  bool comment = false;  // a control ends a comment at the first ')': comments do not nest
  for (std::size_t i = 0; i < block.size(); ++i) {
    const char c = block[i];
    if (c == '(') comment = true;
    if (c == ')') comment = false;
    if (comment || (c != 'G' && c != 'g') || (i > 0 && ascii::is_letter(block[i - 1]))) continue;
    std::size_t j = i + 1;
    while (j < block.size() && (ascii::is_digit(block[j]) || block[j] == '.')) ++j;
    std::string_view n = block.substr(i + 1, j - i - 1);
    while (n.size() > 1 && n[0] == '0' && n[1] != '.') n.remove_prefix(1);  // G01 is G1
    // G20.0 is G20 (a control reads zero decimals so): trailing zeros and the point go.
    if (n.find('.') != std::string_view::npos) {
      while (n.size() > 1 && n.back() == '0') n.remove_suffix(1);
      if (n.back() == '.') n.remove_suffix(1);
    }
    std::string_view want = number;
    while (want.size() > 1 && want[0] == '0' && want[1] != '.') want.remove_prefix(1);
    if (n == want) return true;
  }
  return false;
}

}  // namespace

bool channel_writer::modes_changed_by(const std::vector<std::string>& blocks, std::string_view where,
                                      mode_change& c) {
  // Only a code that differs from the channel's own state counts: a user block that repeats
  // the channel's mode changes nothing.
  const bool inch = m_.program.output_units == output_unit::inch;
  const std::string own_plane = fmt::format("G{}", plane_);
  for (const std::string& b : blocks) {
    for (const std::string* g : {&m_.codes.feed_per_min, &m_.codes.feed_per_rev})
      c.feed = c.feed || (!g->empty() && *g != feed_g_ && has_g_code(b, *g));
    for (const char* g : {"G17", "G18", "G19"}) c.plane = c.plane || (g != own_plane && has_g_code(b, g));
    // G90/G91 are absolute and incremental only where the safe start says G90 (Fanuc lathe
    // G-code system A has no G91, and its G90 is a turning cycle): never written elsewhere.
    // A block with both: a control takes the last of the group; the post takes G91, and puts
    // G90 back after the event either way.
    if (absolute_code_ && has_g_code(b, "G90")) c.incremental = false;
    if (absolute_code_ && has_g_code(b, "G91")) c.incremental = true;
    if (has_g_code(b, inch ? "G21" : "G20")) {
      error(line_, fmt::format("{} writes \"{}\": {} in a program in {} ({}); every later word would be "
                               "read in {}",
                               where, b, inch ? "G21" : "G20", inch ? "inches" : "millimetres",
                               inch ? "G20" : "G21", inch ? "millimetres" : "inches"));
      return false;
    }
  }
  return true;
}

void channel_writer::restore_modes_after(const std::vector<std::string>& blocks, std::string_view where) {
  mode_change c;
  if (!modes_changed_by(blocks, where, c)) return;
  if (c.incremental) out_.block("G90");
  user_incremental_ = false;
  if (c.plane) out_.block(fmt::format("G{}", plane_));
  if (c.feed && !feed_g_.empty()) {
    out_.block(feed_g_);
    last_f_.clear();  // the next feed move writes its F again
  }
}

bool channel_writer::refuse_mode_changes(const std::string& block, std::string_view where) {
  mode_change c;
  if (!modes_changed_by({block}, where, c)) return false;
  if (!c.incremental && !c.plane && !(c.feed && !feed_g_.empty())) return true;
  error(line_, fmt::format("{} gives back \"{}\": it changes the channel's {} in the middle of the post's "
                           "blocks, and no block of the post's puts it back (write it from an event, where "
                           "the post restores the mode after it)",
                           where, block,
                           c.incremental ? "absolute positions (G91)"
                           : c.plane     ? "plane"
                                         : "feed mode"));
  return false;
}

std::string channel_writer::lost_words(std::string_view block, std::string_view replacement) const {
  std::vector<std::string> codes = {"G17", "G18", "G19", "G20", "G21"};
  if (absolute_code_) codes.insert(codes.end(), {"G90", "G91"});
  for (const std::string* g : {&m_.codes.feed_per_min, &m_.codes.feed_per_rev})
    if (!g->empty()) codes.push_back(*g);
  for (const std::string& g : codes)
    if (has_g_code(block, g) && !has_g_code(replacement, g)) return g;
  // Each axis word of the block, outside comments, found as a word of the replacement.
  const program_format& f = m_.program;
  const auto word_at = [](std::string_view text, std::string_view w) {
    for (std::size_t at = text.find(w); at != std::string_view::npos; at = text.find(w, at + 1)) {
      const bool start = at == 0 || !ascii::is_letter(text[at - 1]);
      const std::size_t end = at + w.size();
      const bool stop = end >= text.size() || !(ascii::is_digit(text[end]) || text[end] == '.');
      if (start && stop) return true;
    }
    return false;
  };
  for (std::size_t i = 0; i < block.size(); ++i) {
    if (block[i] == f.comment_open) {
      if (f.comment_close == '\n' || (i = block.find(f.comment_close, i + 1)) == std::string_view::npos)
        break;
      continue;
    }
    if (std::string_view("XYZUVWABCH").find(block[i]) == std::string_view::npos ||
        (i > 0 && ascii::is_letter(block[i - 1])))
      continue;
    std::size_t j = i + 1;
    while (j < block.size() &&
           (ascii::is_digit(block[j]) || block[j] == '.' || block[j] == '-' || block[j] == '+'))
      ++j;
    if (j == i + 1) continue;
    const std::string_view w = block.substr(i, j - i);
    if (!word_at(replacement, w)) return fmt::format("the word {}", w);
    i = j - 1;
  }
  return {};
}

}  // namespace twinpost
