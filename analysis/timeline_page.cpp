// The timeline as one self-contained HTML page: inline SVG and a small inline script,
// nothing fetched (docs/timeline.md, "The page").
#include <algorithm>
#include <cmath>
#include <map>

#include <fmt/format.h>

#include "analysis/timeline_report.hpp"

namespace twinpost {

namespace {

constexpr double page_width = 1200, label_width = 150, right_margin = 30;
constexpr double lane_top = 50, lane_height = 44, lane_gap = 36;
constexpr std::size_t max_drawn_blocks = timeline_max_kept_blocks;  // past this a lane draws operations

// Colours of tools in order of their first call (a qualitative palette); idle is grey.
constexpr const char* palette[] = {"#4e79a7", "#f28e2b", "#59a14f", "#b07aa1", "#edc948",
                                   "#76b7b2", "#ff9da7", "#9c755f", "#e15759", "#8cd17d"};

std::string escape(std::string_view s) {
  std::string o;
  for (char c : s) {
    switch (c) {
      case '&': o += "&amp;"; break;
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '"': o += "&quot;"; break;
      default:
        // Bytes of other encodings (ISO-8859-1 comments) are shown as '?': the page is UTF-8.
        o += (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) ? '?' : c;
    }
  }
  return o;
}

double tick_step(double span) {
  const double raw = span / 10;
  const double p = std::pow(10.0, std::floor(std::log10(raw > 0 ? raw : 1)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * p >= raw) return m * p;
  return 10 * p;
}

class page {
 public:
  explicit page(const timeline& t) : t_(t) {
    const double span = t.cycle > 0 ? t.cycle : 1;
    scale_ = (page_width - label_width - right_margin) / span;
    for (const channel_times& c : t.channels)
      for (const tool_operation& op : c.operations)
        if (!colours_.count(op.tool)) colours_[op.tool] = palette[colours_.size() % std::size(palette)];
  }

  std::string svg() {
    const double height = lane_top + t_.channels.size() * (lane_height + lane_gap) + 10;
    std::string s = fmt::format(
        "<svg id=\"lanes\" xmlns=\"http://www.w3.org/2000/svg\" width=\"{}\" height=\"{}\" "
        "viewBox=\"0 0 {} {}\" font-family=\"sans-serif\" font-size=\"12\">\n",
        page_width, height, page_width, height);
    axis(s, height);
    for (std::size_t i = 0; i < t_.channels.size(); ++i) lane(s, t_.channels[i], lane_y(i));
    links(s);
    critical(s);
    conflicts(s);
    s += "</svg>\n";
    return s;
  }

  std::string legend() const {
    std::string s = "<p class=\"legend\">";
    for (const auto& [tool, colour] : colours_)
      s += fmt::format("<span><i style=\"background:{}\"></i>{}</span>", colour,
                       tool.empty() ? "before the first tool" : escape(tool));
    s += "<span><i class=\"idle\"></i>idle at a wait</span><span><i class=\"crit\"></i>critical path</span>"
         "<span><i class=\"untimed\"></i>block not timed</span></p>\n";
    return s;
  }

 private:
  double x(double seconds) const { return label_width + seconds * scale_; }
  double lane_y(std::size_t i) const { return lane_top + i * (lane_height + lane_gap); }

  void axis(std::string& s, double height) const {
    const double step = tick_step(t_.cycle);
    for (double v = 0; v <= t_.cycle + 1e-9; v += step)
      s += fmt::format(
          "<line x1=\"{0:.1f}\" y1=\"30\" x2=\"{0:.1f}\" y2=\"{1:.1f}\" stroke=\"#e4e4e4\"/>"
          "<text x=\"{0:.1f}\" y=\"24\" text-anchor=\"middle\" fill=\"#555\">{2:g} s</text>\n",
          x(v), height - 10, v);
  }

  void lane(std::string& s, const channel_times& c, double y) {
    s += fmt::format("<g class=\"lane\" data-channel=\"{}\">\n", c.channel);
    s +=
        fmt::format("<text x=\"8\" y=\"{:.1f}\" font-weight=\"bold\">channel {}</text>\n", y + 18, c.channel);
    s += fmt::format("<text x=\"8\" y=\"{:.1f}\" fill=\"#555\">{:.3f} s</text>\n", y + 34, c.end);
    s += fmt::format("<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{}\" fill=\"#f7f7f7\"/>\n",
                     x(0), y, x(c.end) - x(0), lane_height);
    if (!c.kept.empty() && c.kept.size() <= max_drawn_blocks)
      blocks(s, c, y);
    else
      operations(s, c, y);
    for (const wait_stop& w : c.waits) {
      if (w.idle() > 0)
        s += fmt::format(
            "<rect class=\"idle\" x=\"{:.2f}\" y=\"{:.1f}\" width=\"{:.2f}\" height=\"{}\" fill=\"#c9c9c9\" "
            "data-tip=\"{}\"><title>{}</title></rect>\n",
            x(w.arrive), y, x(w.release) - x(w.arrive), lane_height, idle_tip(c, w), idle_tip(c, w));
      s += fmt::format(
          "<path class=\"wait\" d=\"M{0:.2f},{1:.1f} l-5,-8 h10 z\" fill=\"#222\" "
          "data-tip=\"{2}\"><title>{2}</title>"
          "</path>\n",
          x(w.release), y,
          escape(fmt::format("{} at {}:{}, released at {:.3f} s", w.code, c.file, w.where.line, w.release)));
    }
    s += "</g>\n";
  }

  std::string idle_tip(const channel_times& c, const wait_stop& w) const {
    std::string who = w.waited_for > 0 ? fmt::format(" waiting for channel {}", w.waited_for) : "";
    return escape(fmt::format("channel {} idles {:.3f} s at {} ({}:{}){}", c.channel, w.idle(), w.code,
                              c.file, w.where.line, who));
  }

  void operations(std::string& s, const channel_times& c, double y) {
    for (const tool_operation& op : c.operations) {
      const std::string tip = escape(fmt::format("{} from {}:{} ({} blocks) {:.3f} s: {}", op.tool, c.file,
                                                 op.first_line, op.blocks, op.seconds, op.first_text));
      s += fmt::format(
          "<rect class=\"op\" x=\"{:.2f}\" y=\"{:.1f}\" width=\"{:.2f}\" height=\"{}\" fill=\"{}\" "
          "data-tip=\"{}\"><title>{}</title></rect>\n",
          x(op.start), y, std::max(op.seconds * scale_, 0.5), lane_height, colours_[op.tool], tip, tip);
    }
  }

  void blocks(std::string& s, const channel_times& c, double y) {
    std::size_t op = 0;
    for (std::size_t b = 0; b < c.kept.size(); ++b) {
      const timed_block& k = c.kept[b];
      while (op + 1 < c.operations.size() && c.operations[op + 1].first_line <= k.line &&
             c.operations[op + 1].start <= k.start + 1e-9)
        ++op;
      const std::string& tool = c.operations.empty() ? std::string() : c.operations[op].tool;
      const std::string tip = escape(fmt::format("{}:{}  {}  {:.3f} s{}{}", c.file, k.line, k.text, k.seconds,
                                                 tool.empty() ? "" : "  " + tool,
                                                 k.untimed.empty() ? "" : "  not timed: " + k.untimed));
      if (!k.untimed.empty()) {
        s += fmt::format(
            "<path class=\"untimed\" d=\"M{0:.2f},{1:.1f} l-4,8 h8 z\" fill=\"#d62728\" data-tip=\"{2}\">"
            "<title>{2}</title></path>\n",
            x(k.start), y + lane_height, tip);
        continue;
      }
      if (k.seconds <= 0) continue;
      s += fmt::format(
          "<rect class=\"block\" x=\"{:.2f}\" y=\"{:.1f}\" width=\"{:.2f}\" height=\"{}\" fill=\"{}\" "
          "stroke=\"#fff\" stroke-width=\"0.3\" data-tip=\"{}\"><title>{}</title></rect>\n",
          x(k.start), y, std::max(k.seconds * scale_, 0.5), lane_height, colours_[tool], tip, tip);
    }
  }

  // A wait's partners leave together: a dashed line joins their markers.
  void links(std::string& s) const {
    for (std::size_t i = 0; i < t_.channels.size(); ++i)
      for (const wait_stop& w : t_.channels[i].waits) {
        if (w.waited_for == 0) continue;
        const std::size_t j = static_cast<std::size_t>(w.waited_for - 1);
        const double top = std::min(lane_y(i), lane_y(j)),
                     bottom = std::max(lane_y(i), lane_y(j)) + lane_height;
        s += fmt::format(
            "<line class=\"link\" x1=\"{0:.2f}\" y1=\"{1:.1f}\" x2=\"{0:.2f}\" y2=\"{2:.1f}\" "
            "stroke=\"#222\" "
            "stroke-dasharray=\"3,3\"/>\n",
            x(w.release), top, bottom);
      }
  }

  // Each conflict of the interference rule: a red bar across its lane at its block, where the
  // block was kept (timeline_options::keep_blocks), the message as its tip.
  void conflicts(std::string& s) const {
    for (const diagnostic& d : t_.conflicts) {
      const int channel = conflict_channel(t_, d);
      if (channel < 1) continue;
      const channel_times& c = t_.channels[static_cast<std::size_t>(channel - 1)];
      const auto k =
          std::find_if(c.kept.begin(), c.kept.end(), [&](const timed_block& b) { return b.line == d.line; });
      if (k == c.kept.end()) continue;
      const std::string tip = escape(fmt::format("{}:{}: {}", d.file, d.line, d.message));
      s += fmt::format(
          "<rect class=\"conflict\" data-channel=\"{}\" x=\"{:.2f}\" y=\"{:.1f}\" width=\"{:.2f}\" "
          "height=\"{}\" fill=\"none\" stroke=\"#d62728\" stroke-width=\"2\" "
          "data-tip=\"{}\"><title>{}</title></rect>\n",
          channel, x(k->start), lane_y(static_cast<std::size_t>(channel - 1)) - 2,
          std::max(k->seconds * scale_, 3.0), lane_height + 4, tip, tip);
    }
  }

  void critical(std::string& s) const {
    for (const critical_stretch& c : t_.critical) {
      const double y = lane_y(static_cast<std::size_t>(c.channel - 1)) + lane_height + 4;
      s += fmt::format(
          "<rect class=\"critical\" data-channel=\"{}\" x=\"{:.2f}\" y=\"{:.1f}\" width=\"{:.2f}\" "
          "height=\"4\" "
          "fill=\"#d62728\"><title>critical path: channel {} from {:.3f} s to {:.3f} s</title></rect>\n",
          c.channel, x(c.start), y, std::max((c.end - c.start) * scale_, 0.5), c.channel, c.start, c.end);
    }
  }

  const timeline& t_;
  double scale_ = 1;
  std::map<std::string, std::string> colours_;
};

// A picture of one conflict of the interference rule: the two blocks' envelopes in the XZ plane
// of their spindle (Z to the right, r up, the spindle axis dashed), each channel's boxes in its
// colour, the swept tip boxes solid.
std::string meeting_svg(const interference_meeting& g) {
  xz_box all = g.tip_a;
  auto grow = [&](const xz_box& b) {
    all = {std::min(all.r0, b.r0), std::max(all.r1, b.r1), std::min(all.z0, b.z0), std::max(all.z1, b.z1)};
  };
  for (const auto* v : {&g.envelope_a, &g.envelope_b})
    for (const xz_box& b : *v) grow(b);
  grow(g.tip_b);
  const double pad = 10, span_z = all.z1 - all.z0 + 2 * pad, span_r = all.r1 - all.r0 + 2 * pad;
  // At most 360 wide and 300 high, one scale for both axes (true shapes).
  const double scale = std::min(360 / std::max(span_z, 1.0), 300 / std::max(span_r, 1.0));
  const double w = span_z * scale, h = span_r * scale;
  const auto px = [&](double z) { return (z - all.z0 + pad) * scale; };
  const auto py = [&](double r) { return (all.r1 + pad - r) * scale; };
  std::string s = fmt::format(
      "<svg class=\"envelopes\" width=\"{:.0f}\" height=\"{:.0f}\" viewBox=\"0 0 {:.0f} {:.0f}\" "
      "style=\"border:1px solid #ccc;margin:4px\">\n",
      w, h, w, h);
  s += fmt::format(
      "<line x1=\"0\" y1=\"{0:.1f}\" x2=\"{1:.0f}\" y2=\"{0:.1f}\" stroke=\"#888\" "
      "stroke-dasharray=\"6,3\"/>\n",
      py(0), w);
  const auto boxes = [&](const std::vector<xz_box>& v, const xz_box& tip, const char* colour, int channel) {
    for (const xz_box& b : v)
      s += fmt::format(
          "<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" fill=\"{}\" "
          "fill-opacity=\"0.25\" "
          "stroke=\"{}\"><title>channel {}: r {:g}..{:g}, Z {:g}..{:g}</title></rect>\n",
          px(b.z0), py(b.r1), std::max((b.z1 - b.z0) * scale, 1.0), std::max((b.r1 - b.r0) * scale, 1.0),
          colour, colour, channel, b.r0, b.r1, b.z0, b.z1);
    s += fmt::format("<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" fill=\"{}\"/>\n",
                     px(tip.z0), py(tip.r1), std::max((tip.z1 - tip.z0) * scale, 2.0),
                     std::max((tip.r1 - tip.r0) * scale, 2.0), colour);
  };
  boxes(g.envelope_a, g.tip_a, "#1f77b4", g.channel_a);
  boxes(g.envelope_b, g.tip_b, "#ff7f0e", g.channel_b);
  s += "</svg>\n";
  return s;
}

// The inline script: a tooltip for data-tip, and the totals table built from the data.
constexpr const char* script = R"JS(
(function () {
  var data = JSON.parse(document.getElementById('timeline-data').textContent);
  var body = document.getElementById('totals-body');
  data.channels.forEach(function (c) {
    var tr = document.createElement('tr');
    tr.className = 'total';
    tr.setAttribute('data-channel', c.channel);
    [c.channel, c.file, c.busy.toFixed(3) + ' s', c.idle.toFixed(3) + ' s', c.waits.length,
     c.end.toFixed(3) + ' s', c.untimed].forEach(function (v) {
      var td = document.createElement('td');
      td.textContent = v;
      tr.appendChild(td);
    });
    if (c.channel === data.last_channel) tr.className += ' last';
    body.appendChild(tr);
  });
  document.getElementById('cycle').textContent = data.cycle.toFixed(3) + ' s';
  var tip = document.getElementById('tip');
  document.getElementById('lanes').addEventListener('mousemove', function (e) {
    var t = e.target.getAttribute && e.target.getAttribute('data-tip');
    if (!t) { tip.style.display = 'none'; return; }
    tip.textContent = t;
    tip.style.display = 'block';
    tip.style.left = (e.pageX + 12) + 'px';
    tip.style.top = (e.pageY + 12) + 'px';
  });
})();
)JS";

}  // namespace

std::string timeline_page(const timeline& t, std::string_view title) {
  page p(t);
  // Inside <script>, "</" would end the element: JSON may write it "<\/".
  const std::string json = format_timeline_json(t);
  std::string data;
  for (std::size_t i = 0; i < json.size(); ++i) {
    data += json[i];
    if (json[i] == '<' && i + 1 < json.size() && json[i + 1] == '/') data += '\\';
  }
  std::string h = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  h += fmt::format("<title>{}</title>\n", escape(title));
  h += "<style>\n"
       "body{font-family:sans-serif;margin:20px;color:#222}\n"
       "h1{font-size:20px} table{border-collapse:collapse;margin-top:12px}\n"
       "td,th{border:1px solid #ccc;padding:3px 8px;text-align:right} th{background:#eee}\n"
       "tr.last td{font-weight:bold}\n"
       ".legend span{margin-right:14px} .legend i{display:inline-block;width:12px;height:12px;"
       "margin-right:4px;vertical-align:middle}\n"
       ".legend i.idle{background:#c9c9c9} .legend i.crit{background:#d62728;height:4px}\n"
       ".legend i.untimed{background:#d62728;width:8px}\n"
       "#tip{position:absolute;display:none;background:#ffffe0;border:1px solid #999;padding:4px 6px;"
       "font-family:monospace;font-size:12px;white-space:pre;pointer-events:none}\n"
       "</style>\n</head>\n<body>\n";
  h += fmt::format("<h1>{}</h1>\n", escape(title));
  h += fmt::format("<p>machine {}: cycle time {}<b id=\"cycle\">{:.3f} s</b>, channel {} ends last.",
                   escape(t.machine), t.untimed > 0 ? "at least " : "", t.cycle, t.last_channel);
  if (t.untimed > 0) {
    h += fmt::format(" <b>{} block{} not timed</b>:", t.untimed, t.untimed == 1 ? "" : "s");
    for (const untimed_group& g : t.untimed_kinds)
      h += escape(fmt::format(" {} ({}, first at {}:{});", g.why, g.count, g.first.file, g.first.line));
  }
  h += "</p>\n";
  h += "<p class=\"advice\">Balance: ";
  if (t.advice.empty()) h += "no channel idles at a wait.";
  for (std::size_t i = 0; i < t.advice.size(); ++i) h += (i ? "; " : "") + escape(advice_text(t.advice[i]));
  h += "</p>\n";
  if (!t.conflicts.empty()) {  // the interference rule's findings, marked on the lanes too
    h += "<p class=\"conflicts\"><b>Turrets may meet</b> (docs/interference.md):";
    for (const diagnostic& d : t.conflicts)
      if (d.level == severity::error) h += escape(fmt::format(" {}:{}: {}", d.file, d.line, d.message));
    h += "</p>\n";
    // The envelopes of each conflict, XZ view (channel colours: the first blue, the second orange).
    for (const interference_meeting& g : t.meetings)
      h += fmt::format(
          "<figure class=\"meeting\">{}<figcaption>{}:{} (channel {}, blue) and {}:{} (channel {}, "
          "orange) on the {} spindle, Z to the right, r up: {:.1f} mm apart</figcaption></figure>\n",
          meeting_svg(g), escape(g.file_a), g.line_a, g.channel_a, escape(g.file_b), g.line_b, g.channel_b,
          escape(g.spindle), g.distance);
  }
  h += p.legend();
  h += p.svg();
  h += "<table id=\"totals\"><thead><tr><th>channel</th><th>program</th><th>working</th><th>idle</th>"
       "<th>waits</th><th>ends at</th><th>not timed</th></tr></thead><tbody "
       "id=\"totals-body\"></tbody></table>\n";
  h += "<div id=\"tip\"></div>\n";
  h += "<script type=\"application/json\" id=\"timeline-data\">" + data + "</script>\n";
  h += fmt::format("<script>{}</script>\n</body>\n</html>\n", script);
  return h;
}

}  // namespace twinpost
