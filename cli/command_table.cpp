#include "cli/command_table.hpp"

#include <array>
#include <fmt/format.h>

#include "cli/version.hpp"

namespace twinpost::cli {

namespace {

const std::array<command_entry, 6> table{{
    {"parse", "FILE [--json] [--dialect D] | --records", "print the CL event stream, or the record policy",
     "Reads a CL file (APT-style cutter location data of Creo, NX, CATIA, SolidWorks CAM, "
     "Makino or generic ISO 4343) and prints one line per event, or with --json one JSON "
     "object per event. --dialect forces a dialect instead of detecting it. --records prints "
     "the record policy instead: every major word twinpost knows and what a post does with it "
     "(posted, ignored, or an error), with the reason, as a Markdown table.",
     &run_parse},
    {"post",
     "JOB --machine M -o DIR [--layout L] [--sync P] [--dialect D] [--cl-frame F] [--permissive] [--timeline "
     "FILE]"
     " [--compare-optimum] [--json]"
     " [--tool [C:]N]... [--tool-kind K] [--threads N]",
     "post a CL job to NC programs",
     "Posts a CL job for machine M into the folder DIR (made if missing): one program per "
     "channel, or one merged program, as the machine's control expects (--layout split, "
     "merged-appended or merged-sections overrides it). --sync explicit|sequential|optimise|auto says "
     "where the channels wait for each other (optimise: where the post places them for the "
     "shortest cycle of a two-channel job, keeping the job's own SYNC records, "
     "docs/wait-placement.md; auto: at "
     "the job's SYNC records if it has any, else optimise on a machine with [timing] when the "
     "job uses two channels, else at every head switch). --cl-frame mcs|absolute says whether "
     "the points of a turned NX MSYS are written in the CL's MCS or in the absolute frame "
     "(default: the machine's [program] cl_frame, mcs). The programs are written to "
     "temporary names, checked as "
     "'twinpost check' would, and committed as a set only when everything is sound: a failed "
     "run writes nothing and changes nothing in DIR. A major word twinpost does not know stops "
     "the post with an error; --permissive makes it a warning and passes over the record. A "
     "known record the post cannot carry out (STOP is posted, THREAD is not: see 'twinpost "
     "parse --records') stays an error. The summary gives the cycle time and each channel's "
     "idle at its waits when the machine file has [timing]; --timeline FILE writes the "
     "timeline page of the programs into DIR with them; --compare-optimum also says the cycle "
     "--sync optimise would give the job with its own sync records set aside (nothing more is "
     "written); --json prints the summary as one JSON object, with --sync optimise the schedule "
     "(docs/wait-placement.md). A job that moves before any tool call "
     "starts with the tool the machine's [[tool]] table names by the CAM's name of it (NX TOOL "
     "PATH, CATIA TPRINT), else with --tool N (C:N for channel C), called as a tool call record "
     "would be; --tool-kind K is the kind of every tool neither TLDATA nor [[tool]] gives. "
     "With two cores the programs are checked on a second thread while they are written "
     "(--threads 1: after), with the same output.",
     &run_post},
    {"check", "FILE... --machine M [--json]", "check wait synchronisation of NC programs",
     "Checks that the waits of NC programs pair up, in order, and that no channel can "
     "deadlock; then that each channel commands only its own spindles, that no two channels "
     "that may run at the same time command a shared spindle differently, and that no cut "
     "feeds per revolution on a spindle not known to turn. Give one file per channel in channel order, or "
     "one file with the machine's "
     "section markers. --json prints the report as one JSON object.",
     &run_check},
    {"timeline", "FILE... --machine M [-o PAGE.html] [--json]", "cycle time and timeline of NC programs",
     "Times every block of NC programs that check sound with the machine's [timing] (rapid "
     "rates per axis, tool-change and wait times) and its codes (feeds per minute and per "
     "revolution, CSS, dwell, the canned cycles' moves), runs the channels together and prints "
     "the cycle time ('at least' while a block is not timed), each channel's working and idle "
     "time, the blocks it could not time and the longest idles "
     "(where to balance). -o writes one self-contained HTML page: a lane per channel, "
     "operations by tool, waits linked across lanes, the critical path; --json prints the "
     "same data for tools. Files as for check.",
     &run_timeline},
    {"machines", "[--show NAME]", "list the built-in machines, or print one",
     "Lists the built-in machine definitions. --show NAME prints the definition that "
     "--machine NAME would use, as TOML, to copy and edit.",
     &run_machines},
    {"kin", "--machine M [--channel N] [--tool-length L] [--from A,B] [--linearise T] POINT...",
     "joint values of CL points on a machine's kinematic chain",
     "Solves each CL point x,y,z or x,y,z,i,j,k on the [[kinematics]] chain of a channel of "
     "machine M (docs/kinematics.md) and prints the joint values, each point from the one "
     "before: both orientation solutions are weighed by the limits, the preferred tilt sign "
     "and the shortest move. --linearise T also prints the sub-moves that keep the tool tip "
     "within T mm of the straight line. Not used by post yet.",
     &run_kin},
}};

// Roff needs a backslash before a hyphen that must print as one, and an escape before a
// leading dot or quote.
std::string roff(std::string_view s) {
  std::string out;
  for (char c : s) {
    if (c == '-' || c == '\\') out += '\\';
    out += c;
  }
  if (!out.empty() && (out[0] == '.' || out[0] == '\'')) out.insert(0, "\\&");
  return out;
}

}  // namespace

std::span<const command_entry> command_table() { return table; }

std::string command_usage(std::string_view name) {
  for (const command_entry& c : table)
    if (c.name == name) return fmt::format("twinpost {} {}", c.name, c.synopsis);
  return fmt::format("twinpost {}", name);
}

std::string usage_text() {
  std::string s = "usage: twinpost <command> [options]\n\ncommands:\n";
  for (const command_entry& c : table) s += fmt::format("  {} {}\n      {}\n", c.name, c.synopsis, c.summary);
  s += "\nRun 'twinpost <command> --help' for the options of a command;\n"
       "'twinpost --version' prints the version and the commit it was built from.\n";
  return s;
}

std::string man_page() {
  std::string s = fmt::format(".TH TWINPOST 1 \"\" \"twinpost {}\" \"User Commands\"\n", version());
  s += ".SH NAME\ntwinpost \\- postprocessor for multi\\-channel mill/turn machines\n";
  s += ".SH SYNOPSIS\n";
  for (const command_entry& c : table)
    s += fmt::format(".B twinpost {}\n{}\n.br\n", c.name, roff(c.synopsis));
  s += ".B twinpost \\-\\-version\n.br\n.B twinpost \\-\\-help\n";
  s += ".SH DESCRIPTION\n"
       "twinpost reads the CL (cutter location) data that CAM systems write and turns it into the "
       "NC programs of twin\\-turret and multi\\-path machines \\(em one program per turret, meeting "
       "at wait codes \\(em and proves that every wait pairs before it writes a file.\n";
  s += ".SH COMMANDS\n";
  for (const command_entry& c : table)
    s += fmt::format(".TP\n.B {} {}\n{}\n", c.name, roff(c.synopsis), roff(c.details));
  s += ".SH MACHINES\n"
       "\\fB\\-\\-machine\\fR takes a path to a TOML machine file (it holds a '/' or ends in .toml) or a "
       "name. A name is looked up as NAME.toml in, in order: "
       "\\fI$XDG_CONFIG_HOME/twinpost/machines\\fR (default \\fI~/.config/twinpost/machines\\fR), "
       "\\fI/etc/twinpost/machines\\fR, the installation's \\fIshare/twinpost/machines\\fR, and last "
       "among the definitions built into the binary. The post summary names the file used.\n";
  s += ".SH DIAGNOSTICS\n"
       "Problems are reported as a compiler reports them: \\fIfile\\fR:\\fIline\\fR:\\fIcol\\fR: "
       "error: message, then the source line and a caret.\n";
  s += ".SH EXIT STATUS\n"
       ".TP\n.B 0\nsound: the programs were written, or the check found nothing wrong\n"
       ".TP\n.B 1\nerrors in the input (CL job or NC programs); nothing was written\n"
       ".TP\n.B 2\nusage or configuration error (options, machine file, files that cannot be read "
       "or written)\n";
  s += ".SH ENVIRONMENT\n.TP\n.B XDG_CONFIG_HOME\nwhere the user's machine files live "
       "(\\fI$XDG_CONFIG_HOME/twinpost/machines\\fR)\n";
  s += ".SH SEE ALSO\nThe documents in \\fI/usr/share/doc/twinpost\\fR: machines.md (the machine file "
       "schema), checker.md, samples.md, design.md.\n";
  return s;
}

}  // namespace twinpost::cli
