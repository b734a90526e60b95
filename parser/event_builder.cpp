#include "parser/event_builder.hpp"

#include <algorithm>

#include <charconv>
#include <cmath>
#include <fmt/format.h>

#include "parser/detail/word_events.hpp"

namespace twinpost {

using detail::numbers_of;
using detail::upper;

namespace {

// Four numbers and nothing else: a row of the `$$*CATIA0` matrix.
bool matrix_row(std::string_view text, std::vector<double>& out) {
  double row[4];
  int k = 0;
  const char* p = text.data();
  const char* end = p + text.size();
  while (p < end) {
    while (p < end && (*p == ' ' || *p == '\t')) ++p;
    if (p == end) break;
    if (k == 4) return false;
    if (*p == '+') ++p;
    auto [q, ec] = std::from_chars(p, end, row[k]);
    if (ec != std::errc() || !std::isfinite(row[k])) return false;  // from_chars takes "nan"
    ++k;
    p = q;
  }
  if (k != 4) return false;
  out.insert(out.end(), row, row + 4);
  return true;
}

}  // namespace

bool event_builder::to_script(const cl_record& r, int line, event_queue& out) {
  std::string m = upper(r.major);
  if (std::find(script_records_.begin(), script_records_.end(), m) == script_records_.end()) return false;
  end_of_motion_record();
  std::string args = r.kind == record_kind::text ? std::string(r.text) : detail::args_text(r);
  out.push_back({line, passthrough_event{std::move(m), std::move(args), false, true}});
  return true;
}

void event_builder::build(const cl_record& r, int line, event_queue& out, build_issues& issues) {
  if (r.kind != record_kind::comment && r.kind != record_kind::coordinates) after_bad_record_ = false;
  switch (r.kind) {
    case record_kind::comment: comment(r, line, out); return;
    case record_kind::coordinates: {
      if (after_bad_record_) return;  // points of a GOTO that did not parse: reported already
      if (detail::has_bad_number(r, issues)) return;
      if (!in_goto_) {
        issues.push_back({severity::error, r.args.empty() ? 0 : r.args.front().offset,
                          "coordinate line without a preceding GOTO"});
        return;
      }
      const std::span<const double> n = numbers(r);
      if ((n.size() != 3 && n.size() != 6) || n.size() != r.args.size()) {
        issues.push_back({severity::error, r.args.front().offset,
                          fmt::format("a GOTO point takes 3 or 6 numbers, found {}", r.args.size())});
        return;
      }
      point(n, true, motion_kind::go_to, line, out);
      return;
    }
    case record_kind::text: {
      end_of_motion_record();
      if (any_script_records_ && to_script(r, line, out)) [[unlikely]]
        return;
      // PARTNO, PPRINT, INSERT, ...: each has its row in the record table.
      (this->*handler_of(r.major))(r, line, out, issues);
      return;
    }
    case record_kind::statement:
      if (!r.numbers_only && detail::has_bad_number(r, issues)) return skip_record(r.kind);
      if (any_script_records_ && to_script(r, line, out)) [[unlikely]]
        return;
      statement(r, line, out, issues);
      return;
  }
}

void event_builder::skip_record(record_kind seen) {
  if (seen == record_kind::coordinates && in_goto_) return;
  end_of_motion_record();
  after_bad_record_ = true;
}

void event_builder::comment(const cl_record& r, int line, event_queue& out) {
  if (r.data_comment) {
    // Creo `$$->` records: CSYS and CUTTER carry data; the rest are kept as data comments.
    if (word_is(r.major, "CSYS")) {
      out.push_back({line, coordsys_event{"$$-> CSYS", numbers_of(r)}});
      return;
    }
    if (word_is(r.major, "CUTTER")) {
      out.push_back({line, tool_data_event{"$$-> CUTTER", {}, numbers_of(r)}});
      return;
    }
    std::string text = upper(r.major);
    if (!r.args.empty()) text += " / " + detail::args_text(r);
    out.push_back({line, comment_event{comment_kind::data, std::move(text)}});
    return;
  }
  std::string_view t = r.text;
  if (catia_rows_ >= 0) {
    if (matrix_row(t, catia_matrix_) && ++catia_rows_ == 3) {
      out.push_back({catia_line_, coordsys_event{"$$*CATIA0", std::move(catia_matrix_)}});
      catia_matrix_.clear();
      catia_rows_ = -1;
    }
  }
  if (!t.empty() && t.front() == '*') {
    if (t.substr(0, 7) == "*CATIA0") catia_rows_ = 0, catia_matrix_.clear(), catia_line_ = line;
    std::string_view h = t.substr(1);
    while (!h.empty() && h.front() == ' ') h.remove_prefix(1);
    out.push_back({line, comment_event{comment_kind::header, std::string(h)}});
    return;
  }
  if (upper(t.substr(0, 4)) == "UDE:") {
    if (auto s = detail::read_manus_sync(t)) {
      out.push_back({line, *s});
      return;
    }
    out.push_back({line, comment_event{comment_kind::ude, std::string(t)}});
    return;
  }
  out.push_back({line, comment_event{comment_kind::plain, std::string(t)}});
}

void event_builder::finish(build_issues& issues) {
  if (circle_ && !circle_used_)
    issues.push_back({severity::error, 0, "CIRCLE has no end point", circle_->line, circle_->column});
}

}  // namespace twinpost
