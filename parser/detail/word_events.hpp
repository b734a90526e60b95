#pragma once
// Readers for single records whose meaning needs no state beyond the units: SPINDL, FEDRAT,
// COOLNT, CUTCOM, CYCLE, DELAY, AUXFUN/PREFUN, tool calls, sync records. Minor words are
// matched by name, never by position: `SPINDL/RPM,800` and `SPINDL/800,RPM` read alike.
#include <optional>

#include "parser/detail/build_issue.hpp"
#include "parser/events.hpp"
#include "parser/record.hpp"
#include "support/ascii.hpp"

namespace twinpost::detail {

spindle_event read_spindl(const cl_record& r, build_issues& issues);
feed_event read_fedrat(const cl_record& r, unit_system units, build_issues& issues);
coolant_event read_coolnt(const cl_record& r, build_issues& issues);
cutcom_event read_cutcom(const cl_record& r, build_issues& issues);
cycle_event read_cycle(const cl_record& r, build_issues& issues);
/// THREAD/TURN,LEAD,l|PITCH,p[,STARTS,n] and THREAD/OFF; anything else is an error.
std::optional<thread_event> read_thread(const cl_record& r, build_issues& issues);
std::optional<delay_event> read_delay(const cl_record& r, build_issues& issues);
std::optional<aux_event> read_aux(const cl_record& r, bool prefun, build_issues& issues);
/// LOADTL, LOAD/TOOL, SELECT/TOOL, TURRET.
std::optional<tool_event> read_tool(const cl_record& r, tool_source source, build_issues& issues);
std::optional<head_event> read_head(const cl_record& r, build_issues& issues);
std::optional<channel_event> read_channel(const cl_record& r, build_issues& issues);
/// CATIA SYNC/k,c1,c2[,master].
std::optional<sync_event> read_sync(const cl_record& r, build_issues& issues);
/// ICAM SYNCTR/NEXT[,marker[,channels...]]; a marker left out stays unset (the router
/// numbers it per channel).
std::optional<sync_event> read_synctr(const cl_record& r, build_issues& issues);
/// MANUSpost `$$UDE: MANUSPOST - SYNCHRONIZATION/SYNCHRONIZATION NUMBER=n`, if it is one.
std::optional<sync_event> read_manus_sync(std::string_view comment_text);

/// Reports the first argument that was meant as a number but is none (`1e999`: number out
/// of range, `1e`: malformed number, `nan`, `inf`: not a number); true when there was one.
bool report_bad_number(const cl_record& r, build_issues& issues);
/// report_bad_number, without a call for the common record that has no word at all.
inline bool has_bad_number(const cl_record& r, build_issues& issues) {
  for (const cl_arg& a : r.args)
    if (a.kind == arg_kind::word) return report_bad_number(r, issues);
  return false;
}
/// The record's numbers, in order.
std::vector<double> numbers_of(const cl_record& r);
/// The record's arguments as written, joined with ','.
std::string args_text(const cl_record& r);
/// Where a message about the record's arguments points: the first one, else the major word.
inline std::size_t args_offset(const cl_record& r) {
  return r.args.empty() ? r.major_offset : r.args.front().offset;
}
/// An upper-case copy of a word. (ascii::upper_copy under the name the event builders use.)
inline std::string upper(std::string_view w) { return ascii::upper_copy(w); }
/// `v` rounded to the nearest int, clamped to the int range (CL numbers can be anything).
int as_int(double v);

}  // namespace twinpost::detail
