// twinpost post: post a CL job. The synopses of all commands: cli/command_table.cpp.
#include <boost/program_options.hpp>
#include <charconv>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <optional>
#include <unistd.h>

#include "analysis/timeline_report.hpp"
#include "channels/sync_policy.hpp"
#include "cli/cli_util.hpp"
#include "cli/command_table.hpp"
#include "cli/commands.hpp"
#include "cli/interrupt.hpp"
#include "cli/machine_dirs.hpp"
#include "machines/layout_names.hpp"
#include "machines/layout_rules.hpp"
#include "post/post_job.hpp"
#include "support/json.hpp"

namespace twinpost::cli {

namespace po = boost::program_options;

namespace {

constexpr auto layout_option = [](const layout_name& n) { return n.option; };
constexpr auto policy_name = [](const sync_policy_name& n) { return n.name; };

po::options_description post_option_descriptions() {
  static const std::string layouts =
      names_joined(layout_names, layout_option, "|", "|") + " (default: the machine's)";
  static const std::string policies = names_joined(sync_policy_names, policy_name, "|", "|");
  po::options_description opts(command_usage("post"));
  opts.add_options()("help,h", "show this help")("machine,m", po::value<std::string>(),
                                                 "machine name or TOML file")(
      "output,o", po::value<std::string>(), "output folder (made if missing)")(
      "layout", po::value<std::string>(), layouts.c_str())(
      "sync", po::value<std::string>()->default_value("auto"), policies.c_str())(
      "dialect", po::value<std::string>(), "CL dialect (default: detect)")(
      "cl-frame", po::value<std::string>(),
      "mcs|absolute: write NX MSYS points in the CL's MCS or turned into the absolute frame "
      "(default: the machine's [program] cl_frame, mcs)")("permissive",
                                                          "an unknown major word is a warning, not an error")(
      "timeline", po::value<std::string>(), "also write the timeline page (HTML) into DIR under this name")(
      "json", "print the summary as one JSON object (with --sync optimise, the schedule)")(
      "compare-optimum",
      "also work out the cycle of --sync optimise, the job's own sync records set aside, and say it "
      "(nothing more is written)")(
      "tool", po::value<std::vector<std::string>>(),
      "[C:]N: tool N is in the spindle of channel C (default 1) when the job moves before any tool call")(
      "tool-kind", po::value<std::string>(),
      "turn|mill|drill: the kind of a tool neither TLDATA nor [[tool]] gives")(
      "threads", po::value<int>(),
      "1: check the programs after they are written; 2: while they are written, on a second "
      "thread, and work out a 5-axis job's moves ahead on a third (default with two cores); "
      "the output is the same")("job", po::value<std::string>(), "CL file");
  return opts;
}

// The job, --machine and -o are required; false (said on stderr) when one is missing.
bool has_required(const po::variables_map& vm) {
  for (const char* need : {"job", "machine", "output"}) {
    if (!vm.count(need)) {
      fmt::print(stderr, "twinpost post: missing {}\n",
                 std::string(need) == "job" ? "CL job file" : fmt::format("--{}", need));
      return false;
    }
  }
  return true;
}

// --tool's value: "N" (channel 1) or "C:N", whole numbers, C >= 1, N >= 0; nullopt otherwise.
std::optional<std::pair<int, int>> channel_tool(std::string_view s) {
  const auto whole = [](std::string_view d, int& v) {
    const auto [end, ec] = std::from_chars(d.data(), d.data() + d.size(), v);
    return !d.empty() && ec == std::errc() && end == d.data() + d.size() && v >= 0;
  };
  int channel = 1, tool = 0;
  const std::size_t colon = s.find(':');
  if (colon != std::string_view::npos && (!whole(s.substr(0, colon), channel) || channel < 1))
    return std::nullopt;
  if (!whole(colon == std::string_view::npos ? s : s.substr(colon + 1), tool)) return std::nullopt;
  return std::pair{channel, tool};
}

// The options as the library takes them; nullopt (said on stderr) when one names nothing.
std::optional<post_options> read_post_options(const po::variables_map& vm) {
  post_options o;
  o.cl_path = vm["job"].as<std::string>();
  o.out_dir = vm["output"].as<std::string>();
  const auto policy = sync_policy_from_name(vm["sync"].as<std::string>());
  if (!policy) {
    fmt::print(stderr, "twinpost post: --sync must be {}\n",
               names_joined(sync_policy_names, policy_name, ", ", " or "));
    return std::nullopt;
  }
  o.policy = *policy;
  o.permissive = vm.count("permissive") > 0;
  if (vm.count("timeline")) o.timeline_file = vm["timeline"].as<std::string>();
  o.compare_optimum = vm.count("compare-optimum") > 0;
  if (vm.count("layout")) {
    o.layout = layout_from_option(vm["layout"].as<std::string>());
    if (!o.layout) {
      fmt::print(stderr, "twinpost post: --layout must be {}\n",
                 names_joined(layout_names, layout_option, ", ", " or "));
      return std::nullopt;
    }
  }
  if (vm.count("tool"))
    for (const std::string& t : vm["tool"].as<std::vector<std::string>>()) {
      const std::optional<std::pair<int, int>> start = channel_tool(t);
      if (!start) {
        fmt::print(stderr,
                   "twinpost post: --tool must be N or C:N (a tool number, a channel number), not '{}'\n", t);
        return std::nullopt;
      }
      o.start_tools.push_back(*start);
    }
  if (vm.count("tool-kind")) {
    o.tool_kind = vm["tool-kind"].as<std::string>();
    if (o.tool_kind != "turn" && o.tool_kind != "mill" && o.tool_kind != "drill") {
      fmt::print(stderr, "twinpost post: --tool-kind must be turn, mill or drill, not '{}'\n", o.tool_kind);
      return std::nullopt;
    }
  }
  if (vm.count("threads")) {
    o.threads = vm["threads"].as<int>();
    if (o.threads < 1) {
      fmt::print(stderr, "twinpost post: --threads must be 1 or more, not {}\n", o.threads);
      return std::nullopt;
    }
  }
  if (vm.count("cl-frame")) {
    const std::string f = vm["cl-frame"].as<std::string>();
    if (f != "mcs" && f != "absolute") {
      fmt::print(stderr, "twinpost post: --cl-frame must be mcs or absolute, not '{}'\n", f);
      return std::nullopt;
    }
    o.frame = f == "mcs" ? cl_frame::mcs : cl_frame::absolute;
  }
  if (vm.count("dialect")) {
    o.forced_dialect = dialect_from_name(vm["dialect"].as<std::string>());
    if (!o.forced_dialect) {
      fmt::print(stderr, "twinpost post: unknown dialect '{}'\n", vm["dialect"].as<std::string>());
      return std::nullopt;
    }
  }
  return o;
}

// Progress on stderr only for a person watching a terminal: never in logs or pipes.
// `shown` says whether a line was printed that needs clearing.
void show_progress_on_terminal(post_options& o, bool& shown) {
  std::error_code ec;
  const auto total = std::filesystem::file_size(o.cl_path, ec);
  if (ec || !::isatty(2)) return;
  o.progress = [&shown, total, last = std::chrono::steady_clock::now()](std::size_t bytes) mutable {
    auto now = std::chrono::steady_clock::now();
    if (now - last < std::chrono::milliseconds(250)) return;
    last = now;
    shown = true;
    fmt::print(stderr, "\rpost: {:3}% of {} MB", total ? bytes * 100 / total : 100, total >> 20);
  };
}

// The pairs of operations the optimiser kept in the CL's order, and why: the first few (a long
// job's list is long, and the same every post).
void print_kept_apart(const std::vector<std::string>& pairs) {
  constexpr std::size_t shown = 12;
  for (std::size_t i = 0; i < pairs.size() && i < shown; ++i)
    fmt::print("    kept in the CL's order: {}\n", pairs[i]);
  if (pairs.size() > shown)
    fmt::print("    ... and {} more pairs kept in the CL's order\n", pairs.size() - shown);
}

// Where a schedule's channels meet, as the CL's lines a SYNC record would go after (or before,
// at a section's start): "channel 1 after job.cls:26, channel 2 before job.cls:30".
std::vector<std::string> meeting_points(const job_operations& ops, const std::string& file) {
  std::vector<std::string> out;
  for (const plan_section& sec : ops.sections)
    for (const meeting& w : sec.waits) {
      std::string at;
      for (const meeting::at& a : w.channels) {
        const auto side = static_cast<std::size_t>(a.channel);
        const std::vector<channel_op>& list = sec.ops[side];
        const int n = a.position;
        if (list.empty()) continue;
        if (!at.empty()) at += ", ";
        at += n == 0 ? fmt::format("channel {} before {}:{}", ops.channels[side], file, list[0].first_line)
                     : fmt::format("channel {} after {}:{}", ops.channels[side], file,
                                   list[static_cast<std::size_t>(n - 1)].last_line);
      }
      out.push_back(std::move(at));
    }
  return out;
}

// ", the job's 2 sync records kept": the job's own waits, which bind under optimise.
std::string kept_syncs(int n) {
  return n == 0 ? std::string() : fmt::format(", the job's {} sync record{} kept", n, n == 1 ? "" : "s");
}

void print_summary(const post_summary& s, const printing_sink& sink, const located_machine& found,
                   const std::string& cl_file) {
  // One channel waits for nobody: no policy to report.
  const std::string waits = s.channels == 1 ? "no waits (one channel)"
                                            : fmt::format("{} wait{} ({})", s.waits, s.waits == 1 ? "" : "s",
                                                          sync_policy_to_name(s.policy));
  fmt::print("post: {} records, {} channel{}, {} blocks, {}, {} warning{}\n", s.records, s.channels,
             s.channels == 1 ? "" : "s", s.blocks, waits, sink.warnings(), sink.warnings() == 1 ? "" : "s");
  fmt::print("  machine {} ({})\n", found.def.name, found.origin);
  for (const std::string& f : s.files) fmt::print("  wrote {}\n", f);
  if (s.timing && s.sequential_cycle) {
    const double seq = *s.sequential_cycle, now = s.timing->cycle;
    const double percent = seq > 0 ? (seq - now) / seq * 100 : 0.0;
    fmt::print(
        "  waits placed for the shortest cycle: {:.3f} s against {:.3f} s sequential ({}), {} post{}{}\n",
        now, seq, percent >= 0.05 ? fmt::format("-{:.1f} %", percent) : std::string("no shorter"), s.passes,
        s.passes == 1 ? "" : "s", kept_syncs(s.schedule ? s.schedule->kept_syncs : 0));
    print_kept_apart(s.kept_apart);
  }
  if (s.timing && s.optimum_cycle) {
    const double best = *s.optimum_cycle, now = s.timing->cycle;
    const double percent = now > 0 ? (now - best) / now * 100 : 0.0;
    // Longer where the job's own waits let operations overlap that the optimiser keeps in the
    // CL's order (tools of unknown size, cuts close together): said as such.
    fmt::print(
        "  with the waits placed by --sync optimise (its sync records, if any, set aside): {:.3f} s against "
        "{:.3f} s ({}), {} post{}, not written\n",
        best, now,
        percent >= 0.05    ? fmt::format("-{:.1f} %", percent)
        : percent <= -0.05 ? fmt::format("+{:.1f} %: the job's own waits give the shorter cycle", -percent)
                           : std::string("the same"),
        s.optimum_passes, s.optimum_passes == 1 ? "" : "s");
    // Where its waits would go: the SYNC records that give that cycle (the first few).
    if (s.optimum_schedule) {
      const std::vector<std::string> at = meeting_points(*s.optimum_schedule, cl_file);
      constexpr std::size_t shown = 12;
      for (std::size_t i = 0; i < at.size() && i < shown; ++i) fmt::print("    it meets at: {}\n", at[i]);
      if (at.size() > shown) fmt::print("    ... and {} more meetings\n", at.size() - shown);
    }
    print_kept_apart(s.optimum_kept_apart);
  } else if (!s.optimum_unknown.empty()) {
    fmt::print("  --sync optimise (its sync records, if any, set aside) gives no cycle to compare: {}\n",
               s.optimum_unknown);
  }
  if (s.timing)
    fmt::print("{}", format_timeline_text(*s.timing, "  "));
  else
    fmt::print("  cycle time not known: machine {} has no [timing] table\n", found.def.name);
}

// A schedule as JSON: the channels, per section each one's operations (CL lines, seconds) and
// where they meet (each wait the operations each channel has done before it, null for a channel
// it does not name), and the pairs kept in the CL's order.
void append_schedule_json(std::string& out, const job_operations& ops, std::optional<double> sequential,
                          int posts, const std::vector<std::string>& kept_apart) {
  out += fmt::format(
      "{{\"channels\":[{}],\"sequential_cycle\":{},\"posts\":{},\"kept_syncs\":{},"
      "\"sections\":[",
      fmt::join(ops.channels, ","), sequential ? fmt::format("{:.3f}", *sequential) : std::string("null"),
      posts, ops.kept_syncs);
  for (std::size_t i = 0; i < ops.sections.size(); ++i) {
    const plan_section& sec = ops.sections[i];
    out += fmt::format("{}{{\"together\":{},\"operations\":[", i ? "," : "", sec.together);
    for (std::size_t side = 0; side < sec.ops.size(); ++side) {
      out += side ? ",[" : "[";
      for (std::size_t k = 0; k < sec.ops[side].size(); ++k) {
        const channel_op& op = sec.ops[side][k];
        out += fmt::format("{}{{\"cl_lines\":[{},{}],\"seconds\":{:.6f}}}", k ? "," : "", op.first_line,
                           op.last_line, static_cast<double>(op.us) / 1e6);
      }
      out += ']';
    }
    out += "],\"waits\":[";
    for (std::size_t w = 0; w < sec.waits.size(); ++w) {
      std::vector<std::string> after(sec.ops.size(), "null");
      for (const meeting::at& a : sec.waits[w].channels)
        if (a.channel >= 0 && static_cast<std::size_t>(a.channel) < after.size())
          after[static_cast<std::size_t>(a.channel)] = std::to_string(a.position);
      out += fmt::format("{}{{\"after\":[{}]}}", w ? "," : "", fmt::join(after, ","));
    }
    out += "]}";
  }
  out += "],\"kept_apart\":[";
  for (std::size_t i = 0; i < kept_apart.size(); ++i) {
    if (i) out += ',';
    append_json_string(out, kept_apart[i]);
  }
  out += "]}";
}

// The summary as one JSON object (docs/wait-placement.md, "post --json"): what was written,
// the cycle, and under --sync optimise the schedule the programs follow.
void print_json_summary(const post_summary& s, const printing_sink& sink, const located_machine& found) {
  std::string out = "{";
  const auto key = [&](std::string_view k) {
    if (out.size() > 1) out += ',';
    append_json_string(out, k);
    out += ':';
  };
  const auto seconds = [](double v) { return fmt::format("{:.3f}", v); };
  key("machine");
  append_json_string(out, found.def.name);
  key("records");
  out += fmt::format("{}", s.records);
  key("channels");
  out += fmt::format("{}", s.channels);
  key("blocks");
  out += fmt::format("{}", s.blocks);
  key("waits");
  out += fmt::format("{}", s.waits);
  key("policy");
  append_json_string(out, sync_policy_to_name(s.policy));
  key("warnings");
  out += fmt::format("{}", sink.warnings());
  key("files");
  out += '[';
  for (std::size_t i = 0; i < s.files.size(); ++i) {
    if (i) out += ',';
    append_json_string(out, s.files[i]);
  }
  out += ']';
  key("cycle");
  out += s.timing ? seconds(s.timing->cycle) : std::string("null");
  if (s.schedule) {
    key("schedule");
    append_schedule_json(out, *s.schedule, s.sequential_cycle, s.passes, s.kept_apart);
  }
  if (s.optimum_cycle || !s.optimum_unknown.empty()) {
    key("optimum");
    if (s.optimum_cycle) {
      out += fmt::format("{{\"cycle\":{},\"posts\":{}", seconds(*s.optimum_cycle), s.optimum_passes);
      if (s.optimum_schedule) {
        out += ",\"schedule\":";
        append_schedule_json(out, *s.optimum_schedule, std::nullopt, s.optimum_passes, s.optimum_kept_apart);
      }
      out += '}';
    } else {
      out += "{\"unknown\":";
      append_json_string(out, s.optimum_unknown);
      out += '}';
    }
  }
  out += "}\n";
  fmt::print("{}", out);
}

}  // namespace

int run_post(const args& a) {
  const po::options_description opts = post_option_descriptions();
  po::positional_options_description pos;
  pos.add("job", 1);
  po::variables_map vm;
  if (const std::optional<int> done = parse_command(a, opts, pos, vm, "post", to_string(opts))) return *done;
  if (!has_required(vm)) return 2;
  std::optional<post_options> o = read_post_options(vm);
  if (!o) return 2;
  const located_machine found = locate_machine(vm["machine"].as<std::string>());
  const machine& m = found.def;
  if (const std::string why = layout_problem(m, o->layout.value_or(m.layout)); !why.empty()) {
    fmt::print(stderr, "twinpost post: --layout: machine '{}': {}\n", m.name, why);
    return 2;
  }
  bool shown = false;
  show_progress_on_terminal(*o, shown);
  printing_sink sink;
  install_interrupt_cleanup();
  const post_summary s = post_job(*o, m, sink);
  if (shown) fmt::print(stderr, "\r{:30}\r", "");
  if (!s.ok) {
    fmt::print(stderr, "post: failed with {} error{}; no file written\n", sink.errors(),
               sink.errors() == 1 ? "" : "s");
    return 1;
  }
  if (vm.count("json"))
    print_json_summary(s, sink, found);
  else
    print_summary(s, sink, found, o->cl_path);
  return 0;
}

}  // namespace twinpost::cli
