#pragma once
// Turns one channel's routed events into NC blocks (a lathe's G18, X in diameter, Z; on a
// channel whose machine gives it a kinematic chain, multi-axis moves: channel_multiaxis.cpp
// and channel_plane.cpp), keeping
// that channel's modal state: tool, spindle and its mode, feed mode, motion G-code, last
// axis words (modal suppression), cutter compensation, an active drilling cycle.
// Lengths are written in the machine file's output units (mm or inch): the CL's are converted
// on the way.
#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "channels/router.hpp"
#include "formats/block_writer.hpp"
#include "formats/number_format.hpp"
#include "kinematics/linearise.hpp"
#include "machines/machine.hpp"
#include "machining/kin_lookahead.hpp"
#include "parser/events.hpp"
#include "scripting/lua_script.hpp"
#include "support/diagnostics.hpp"

namespace twinpost {

/// What the channels of one job do to the machine's spindles, shared by their writers: which
/// spindle some channel starts (a speed) anywhere in the job. A channel that cuts on a shared
/// spindle it does not start itself relies on another's start (analysis/shared_resources
/// orders the two); one that no channel ever starts is an error at the end of the job.
struct job_spindles {
  /// Per machine spindle (index into machine::spindles), per channel (number - 1): whether
  /// that channel starts it somewhere in the job.
  std::vector<std::vector<char>> started;
  /// Whether a channel other than `channel` starts spindle `index` somewhere in the job.
  bool started_by_other(std::size_t index, int channel) const {
    for (std::size_t c = 0; c < started[index].size(); ++c)
      if (started[index][c] && static_cast<int>(c) + 1 != channel) return true;
    return false;
  }
  /// The CL source line `line` while its record is being written (for a diagnostic given
  /// later, at the end of the job); may be empty.
  std::function<std::string(int line)> quote;
};

/// The machine's script, shared by a job's writers (post/post_job loads it once per job). After
/// its first error it is not called again: the post has failed, one message says why.
struct job_script {
  scripting::lua_script* lua = nullptr;
  bool failed = false;
};

/// The diagnostic of a script error: `NAME.lua:LINE: error: message`, the script's line and a
/// caret under its first word (machining/channel_script.cpp).
diagnostic script_diagnostic(const scripting::script_error& e);

/// Sees what a channel writer writes and the records it writes it for (post wires the
/// comparison with the CL to it: analysis/cl_compare.hpp).
class write_observer {
 public:
  virtual ~write_observer() = default;
  /// Every line of the program as written, the head's first, without its line end.
  virtual void line(std::string_view text) = 0;
  /// The job's units (UNITS record).
  virtual void units(unit_system u) = 0;
  /// A record of the channel, after its blocks are written (`both`: a HEAD/BOTH copy).
  virtual void record(const event& e, bool both) = 0;
  /// Whether line() is to be called (set_observer asks once).
  virtual bool wants_lines() const { return true; }
};

class channel_writer : private scripting::script_host, private block_writer::block_filter {
 public:
  /// Writes the channel's blocks to `path`, framed by `frame` (see block_writer).
  channel_writer(const machine& m, const channel_def& ch, const std::string& path, diagnostic_sink& diags,
                 std::string cl_file, block_writer::framing frame = {});

  /// The job's units (UNITS record); values are converted to the program's output units.
  void set_units(unit_system u) {
    release_held(std::nullopt);          // records held at the pole came in the units before
    if (observer_) observer_->units(u);  // (after them: the comparison reads them in those units)
    cl_mm_ = u == unit_system::inch ? 25.4 : 1.0;
    scale_ = cl_mm_ * out_per_mm_;
  }
  void on_event(const event& e, bool both);
  /// Shows `o` every line written and every record written (nullptr: none, the default).
  void set_observer(write_observer* o) {
    observer_ = o;
    observe_lines_ = o && o->wants_lines();
  }
  /// One record of the channel, in order (on_event's work once nothing is held).
  void process_event(const event& e, bool both);
  /// Balance cutting (HEAD/BOTH): `master` is the writer of the channel that serves head 1,
  /// which alone commands the spindle; this channel's copy writes no spindle code (no S, M3,
  /// M4, M5, G96, G97, select or clamp block of a workpiece spindle) and cuts on the master's
  /// workpiece spindle. Fanuc B-63944EN-1 §7.1 (balance cut G68/G69: two tool posts on one
  /// workpiece); the S code in path 1's program only as the issue reports the Fanuc manuals,
  /// UNVERIFIED in the pages read.
  void set_balance_master(const channel_writer* master) { balance_master_ = master; }
  /// A job that moves before any tool call in this channel: `tool`, when given, is the tool in
  /// the channel's spindle (post --tool); a tool the machine's [[tool]] table names by the
  /// CAM's name of it comes first. `kind` ("turn", "mill", "drill" or empty) is the kind of
  /// every tool the CL and the [[tool]] table leave without one (post --tool-kind).
  void start_with(std::optional<int> tool, std::string_view kind);
  /// The frame NX MSYS points are written in (post --cl-frame), instead of the machine's.
  void write_in(cl_frame f) { frame_ = f; }
  /// The job's record of spindle starts, shared by all its writers (see job_spindles); without
  /// one a cut on a spindle this channel has not started is an error at once.
  void share_spindles(job_spindles* j) { job_spindles_ = j; }
  /// The job's script ([events] script; machining/channel_script.cpp): its hooks run at the
  /// writer's event points, its on_block (when it has one) sees every block, the header's
  /// and the footer's too (frame_block).
  void use_script(job_script* s);
  /// A header (`header`) or footer block of the program's frame through the script's on_block:
  /// the blocks written in its place, in order (post.emit's, then the block kept or replaced;
  /// none: dropped). Each block (`index`: its place in the machine file's list) is asked
  /// once: the frame written again under the program's name (formats/program_layout) gets the
  /// same answer, the block's new text where it was kept as it was. frame_request::edit_block.
  std::vector<std::string> frame_block(const std::string& b, bool header, std::size_t index);
  void on_wait(const wait_mark& w);
  /// Ends the body: coolant and spindle off are the footer's job; closes the file.
  void finish();
  /// The footer blocks the channel's end already has in force: its last coolant-off and
  /// spindle-stop blocks, when nothing turned the coolant or the spindle on after them
  /// (program_layout's frame_tail leaves them out, so no M9 or M5 is written twice), and the
  /// home blocks a tool left in the cut went out by at the end (leave_cut), when no user block
  /// moved an axis after them.
  std::vector<std::string> footer_in_force() const;
  long blocks() const { return out_.blocks(); }
  const std::string& head_written() const { return out_.head_written(); }
  /// The bytes of the program written so far (block_writer::bytes_out): where a record shown
  /// to the observer stands in its program.
  std::uint64_t bytes_written() const { return out_.bytes_out(); }
  /// The bytes written so far to the relay now (block_writer::pass_now).
  void pass_written() { out_.pass_now(); }
  /// The moves worked out ahead on another thread (machining/kin_lookahead.hpp); nullptr: none.
  void set_lookahead(const kin_lookahead* ahead) { ahead_ = ahead; }
  /// Another thread writes the program's file (block_writer::relay).
  void set_relay(std::unique_ptr<block_writer::relay> r) { out_.set_relay(std::move(r)); }
  int waits() const { return waits_; }
  /// The CL line of each wait block written, in order (to report the checker's findings).
  const std::vector<int>& wait_cl_lines() const { return wait_cl_lines_; }
  /// A block that may carry a finding of the shared-resource rules: one with an S or M word
  /// (spindle commands), or the first G1/G2/G3 after a wait or after such a block (a cut).
  struct noted_block {
    int segment = 0;   ///< waits written before it
    std::string text;  ///< the line as written
    int cl_line = 0;   ///< the CL record being written
  };
  /// Those blocks, in order (post/sync_at_cl moves findings at them to their CL records).
  const std::vector<noted_block>& noted_blocks() const { return noted_; }
  /// The CL line of every block written after the head (no comment lines), in order, for a
  /// channel the turret interference rule watches (machine.interference); else empty. The
  /// rule's findings may be at any move (post/sync_at_cl).
  /// Kept in an anonymous temporary file while the post runs (memory stays flat however long
  /// the programs are), read back one at a time: asked for only at the rule's findings.
  /// `i` < block_cl_count(); throws config_error when the file cannot be read.
  int block_cl_line(std::size_t i) const;
  std::size_t block_cl_count() const { return block_cl_count_; }
  /// The index (for block_cl_line) of each wait block, in order (the same channels).
  const std::vector<std::size_t>& wait_block_indices() const { return wait_block_; }

 private:
  /// The CL line of the block being written, to block_cl_'s file.
  void note_block_cl();
  void motion(const motion_event& m, int line);
  void arc(const arc_event& a, int line);
  void spindle(const spindle_event& s, int line);
  /// A SPINDL of the CL (or of the tool table), with the [events] blocks around it.
  void spindle_record(const spindle_event& s, int line);
  /// At a tool's first move without a SPINDL since its call: the [[tool]] table's speed.
  void table_speed(int line);
  /// The spindle a SPINDL without a spindle word turns: the workpiece spindle, or the live one
  /// for a milling tool or an off-centre drill (machining/channel_spindle.cpp); nullptr after an
  /// error.
  const spindle_def* spindle_for_tool(const spindle_event& s, int line);
  /// The channel works on workpiece spindle `s` from now on: its work offset, its Z sense.
  void work_on(const spindle_def& s);
  /// The select code of `s` (Integrex M901 main, M902 second spindle), unless it is the last
  /// one this channel wrote; a spindle without one (the live spindle) selects nothing.
  void select_spindle(const spindle_def* s);
  /// False, after an error, when a drill turning with the part (on-centre axial drilling on
  /// the workpiece spindle) would feed off the centre line.
  bool drill_on_centre(double x_cl, int line);
  /// A machining centre's channel: the spindle that turns the tools is the one the channel's
  /// work is on, so the part stands still (drills anywhere, never needs the centre line).
  bool part_stands_still() const { return work_ != nullptr && m_.spindle(ch_.live_spindle) == work_; }
  /// False, after an error (once per tool axis), when the tool axis in force is not along Z:
  /// twinpost writes no rotary axes yet, so a tilted or radial tool cannot be posted.
  bool tool_along_z(int line);
  /// The kind the machine's tool table gives `tool`, where the CL gave none; a TLDATA that
  /// says otherwise is an error (one of the two is wrong about the tool in the turret).
  void table_kind(int tool, int line);
  /// TLDATA/MILL, DRILL, TURN: the kind of the tool called next (or of the one just called).
  void tool_data(const tool_data_event& t);
  /// A step of a part transfer (channels/router sends each channel its steps).
  void transfer(const transfer_event& t, int line);
  void feed(const feed_event& f, int line);
  void tool(const tool_event& t, int line);
  /// Tool `tool` (called by `word` at `line`) is the one in the spindle from now on, its kind
  /// from TLDATA or the tool table; also after a refused call (the post has failed, but the
  /// records after it are judged with the tool the CL called, without errors that follow).
  void take_tool(int tool, int line, const char* word);
  /// One hole of the cycle in force at CL point `p` (channel_cycles.cpp).
  void cycle_point(const vec3& p, int line);
  /// Where a hole at CL point `p` of the cycle in force is approached: above it on the
  /// cycle's retract plane (RTRCTO, else the R plane: RAPTO or CLEAR above the top).
  vec3 cycle_approach(const vec3& p) const;
  /// A hole's cycle whose first point comes straight from a cut below its R level: an error
  /// (true) where the positioning would run through the part.
  bool hole_from_cut(const vec3& p, int line);
  // Frames of the CL (machining/channel_frames.cpp).
  /// NX MSYS: its rotation (MCS to absolute) turns every later point and tool axis; SolidWorks
  /// CSYS: a rigid frame about the world origin names the operation's tool axis (the points stay
  /// in the world frame, TRNTYP/WORLD). A frame that is not rigid is an error.
  void frame(const coordsys_event& c, int line);
  /// The event's points and axes turned by MSYS's rotation; false (with the error) for a record
  /// whose meaning under the turn is not known (a drilling cycle's levels).
  bool turn_to_msys(event& e);
  /// Under a turned CSYS: false (with the error, once per CSYS) for a GOTO whose tool axis is
  /// not the CSYS's Z.
  bool csys_axis_fits(const event& e);
  struct hole;
  /// To the hole's retract plane: up first, across, down last.
  void to_hole(const hole& h, int line);
  /// C to a face hole's angle and clamped (to_hole, at the plane it turns on).
  void turn_c_to_hole(double degrees);
  /// Plain moves: rapid to the retract and R planes, feed (in pecks), dwell, rapid out.
  void expanded_hole(const hole& h, int line);
  /// The machine's canned cycle `code` ([cycles]) for a drilled hole.
  void canned_hole(const hole& h, const std::string& code, int line);
  /// A tap: the canned rigid or floating cycle, or synchronised feeds with the spindle reversed.
  void tap_hole(const hole& h, int line);
  /// The cycle block, the cancel code and the move back to the retract plane.
  void cycle_block(const hole& h, const std::string& code, double q, double pitch, int line);
  /// A dwell block from the machine's dwell template, if the time fits its word.
  void write_dwell(double seconds);
  void feed_back_due(const event& e);  // the mode a dwell left, before the next record (feed_back_)
  /// M0/M1, then the spindle and coolant blocks in force again: the stop turns them off on
  /// most lathes, and cycle start must not resume cutting with a still spindle.
  void program_stop(bool optional);
  /// The machine's home blocks (X, then Z), then a length-offset cancel that waited for them.
  void go_home();
  /// From a cut, the home blocks along the tool (along_tool) now, the rest at go_home; a
  /// warning where the way out is not known (a turning tool).
  /// `at_end`: the job's end (the last wait, or the footer of a channel without one): a tool whose
  /// way out is not known is left to the footer's home as before, without the warning (the CL's
  /// last feed of a turning tool, a part-off or a face, is most often its way out).
  void leave_cut(bool at_end = false);
  /// Where the tool is in a cut (its last move a feed) and the axis along it is known: the
  /// addresses that move along it (Z and W for an axial tool, X and U for a radial one); "".
  std::string_view along_tool() const;
  /// A live tool on an indexing head, indexed for the part's spindle.
  bool head_live() const;
  /// The tool along the spindle axis leaves a cut along it: a drill, or a live tool on a head.
  bool leaves_axially() const;
  /// From a cut, an axial tool on a spindle that faces the main one (Z reversed): no home block
  /// leaves along it (Z's home lies beyond that spindle's face, deeper into its part), so it goes
  /// back along its axis to the most retracted level of its rapid points above where it stands
  /// (since its call or the work spindle's change), in the work frame; an error where no rapid
  /// gives that level or the spindle is held as a C axis (review 37 H2, review 38, attack 69 M2).
  void retract_facing();
  /// A rapid of the tool to CL height `z`: a level clear of the part (retract_facing).
  void note_clear(const vec3& p) { clear_at_[clear_n_++ % clear_at_.size()] = p; }
  /// The length offset (G43, G43.4, the plane's G43) cancelled, with the tool at its home: the
  /// cancel may move Z by the tool's length, so away from home it waits for the home blocks
  /// (docs/machines.md, "Length offset cancel").
  void cancel_length_offset();
  /// The spindle stopped for a tool change turns again (before the first move after it).
  /// The first move after a tool change that stopped the spindle (spindle_held_) or kept a
  /// shared one turning (spindle_kept_): the new tool must want the spindle that turned; a held
  /// one is started again.
  void resume_spindle(int line);
  /// False (with the error) when the spindle a feed move cuts on is not known to turn: this
  /// channel's SPINDL/OFF stopped it, or no SPINDL started it (unless the tool needs none,
  /// [[tool]] spindle = false, or another channel may start a shared one: judged at finish()).
  bool spindle_turning(int line);
  /// The index of spindle `s` in the machine's spindles.
  std::size_t spindle_index(const spindle_def& s) const {
    return static_cast<std::size_t>(&s - m_.spindles.data());
  }
  /// The error for a cut on spindle `s` that nothing started: in this channel, or (`job`) in
  /// any channel of the job.
  std::string not_started(const spindle_def& s, bool job) const;
  /// Notes in the job's record that this channel starts the spindle in force.
  void note_start();
  /// Why an axial hole off the centre line cannot be drilled here, and what would drill it:
  /// the live tool with the part held as C on a mill/turn channel, nothing on a plain lathe's.
  std::string off_centre_hole_needs() const;
  /// The error for a move before any tool call in this channel, once per channel.
  void no_tool(int line);
  /// Before a record that needs the tool (a move, SPINDL, COOLNT, a cycle, CUTCOM) with no
  /// tool called yet, or with a CAM name of a tool since the last call: calls the tool the
  /// CAM's name or (with none called) post --tool gives, as a tool call record would
  /// (machining/channel_start_tool.cpp). False when no tool is in force after it.
  bool start_tool(int line);
  /// A tool call record, or the post's own (start_tool): the cycle in force ended, the
  /// multi-axis state closed and opened for the new tool.
  void call_tool(const tool_event& t, int line);
  /// Remembers the CAM's name of its tool from a text record (TOOL PATH, TPRINT).
  void note_cam_tool(const text_event& t, int line);
  /// COOLNT: flood (ON, FLOOD) writes the machine's coolant-on block, MIST, THRU and AIR their
  /// pairs (codes.coolant_mist ...); a kind the machine file gives no code for (and TAP) is
  /// an error, never plain flood. OFF writes the off block of the kind in force.
  void coolant(const coolant_event& c, int line);
  /// True when the writer carries out every word of cycle `c`; else an error naming the first
  /// word it would drop (a tap, a bore, a retract plane, a peck of another dialect...).
  bool cycle_supported(const cycle_event& c, int line);
  // Threading and grooving (machining/channel_thread.cpp), as the machine's [cycles] say.
  /// True when `c` is a lathe cycle (THREAD, GROOVE) this machine writes with every word the
  /// record gives; else an error naming the record's first word it cannot carry out.
  bool lathe_cycle_supported(const cycle_event& c, int line);
  /// The GOTO of a CYCLE/THREAD (the thread's end at full depth) or CYCLE/GROOVE (the groove's
  /// first plunge on the surface); the tool starts from pos_ and ends there again.
  void thread_cycle_point(const vec3& p, int line);
  void groove_cycle_point(const vec3& p, int line);
  /// THREAD/TURN and THREAD/OFF: later feed moves are synchronised passes until OFF.
  void thread_mode(const thread_event& t, int line);
  /// One THREAD/TURN feed move: G32 to `p` at the lead in force.
  void thread_pass(const vec3& p, int line);
  /// True when the spindle turns at a constant speed (threading needs it); else an error.
  bool spindle_ready_for_thread(std::string_view what, int line);
  /// Appends " F<lead>" (mm per turn, four places) to `out` after checking the format.
  /// True (with the error) when a thread would be written in inch output.
  bool inch_thread_refused(std::string_view what, int line);
  /// `v` (in the output units) in the control's least input increment, for words read
  /// without a point (G76 P/Q, G75 P/Q).
  long long increments(double v) const;
  bool append_lead(text_buffer& out, double lead_mm);
  /// After a thread: the feed mode in force before it again (written only if one was).
  void restore_feed_mode(bool had_mode, bool per_rev);
  void linear(bool rapid, double x_cl, double y_cl, double z_cl, int line);
  /// CUTCOM: G41/G42 (swapped where the frame turns the plane over, sense_reversed) with the
  /// D register codes.cutcom_offset says, or G40, for the next move.
  void cutcom(const cutcom_event& c, int line);
  /// True when G41 or G42 (with its D word) waits for the next move.
  bool comp_starting() const { return pending_g_.starts_with("G41") || pending_g_.starts_with("G42"); }
  // Mill/turn (machining/channel_millturn.cpp): live tools on a channel with a C axis.
  /// True while a live tool turns on a channel with a C axis (the workpiece spindle is held).
  bool live_tool() const;
  /// The workpiece spindle becomes the C axis (spindle.c_on), X in radius (milling.radius_input);
  /// false, with the error, on a spindle that cannot be held.
  bool enter_c_axis(int line);
  /// Polar interpolation off, C unclamped, X in diameter, the spindle a turning spindle again.
  void leave_c_axis();
  void set_x_radius(bool radius);
  /// Polar interpolation on, for a first move to `first` (CL units): Y to the centre line, with
  /// a length offset due and a `rapid` first move the tool at `first`'s radius and height at C0
  /// (the Fusion Integrex post's `G0 G43 X.. Y0. Z.. H#3020`), C at 0 and free, the mode's codes.
  void enter_polar(const vec3& first, bool rapid);
  void leave_polar();
  /// G0 C<degrees>, unclamping first; the C frame's rotation follows it.
  void position_c(double degrees);
  void clamp_c();
  /// True when a move along the spindle axis is written in polar interpolation.
  bool face_polar() const;
  void polar_linear(bool rapid, const vec3& p, int line);
  /// The indexing head to the angle the tool in force needs (channel.head_index), homing
  /// first when the tool is not home; false after an error.
  bool index_head(int line);
  /// For linear(): on a channel with a C axis, `x`, `y` in the frame C has turned the part to
  /// (C positioned first where a rapid needs it); false when the move was written in polar
  /// interpolation or refused.
  bool c_frame_move(bool rapid, double& x, double& y, double& z, int line);
  /// The CL point (x, y) in the frame of the C axis's angle (itself outside C mode, and for
  /// a cross hole's points, which come in the turned frame already).
  std::pair<double, double> c_frame(double x, double y) const {
    if (!c_mode_ || radial_frame_) return {x, y};
    return {x * c_cos_ + y * c_sin_, -x * c_sin_ + y * c_cos_};
  }
  /// An axial hole off centre at a C position (milling.face_holes = "c_axis"): C is turned onto
  /// it and clamped by to_hole (c_hole_deg_), once the tool is out of the last hole; false when
  /// the hole is not one.
  bool c_axis_hole(const vec3& p);
  /// Cross holes: C to `degrees` and clamped, the frame turned (milling.radial_frame_on);
  /// false, with the error, where the machine gives no frame.
  bool enter_radial_frame(double degrees, int line);
  void leave_radial_frame();
  /// CL point `p` under a radial tool axis as `q` in the turned frame (entered first).
  bool radial_point(const vec3& p, vec3& q, int line);
  /// Cross holes drilled along X with the lathe's side cycles (milling.cross_holes =
  /// "side_cycle", Fanuc G87/G88): C turned to the tool axis's angle and clamped, CL point `p`
  /// as `q` in the turned frame's terms (X the part's -Z, Y beside the radial line, Z the
  /// radius). False, with the error, for a hole beside the radial line.
  bool side_point(const vec3& p, vec3& q, int line);
  /// A move of a radial tool with cross_holes = "side_cycle": C at the tool axis's angle, X
  /// along the tool. True when linear() writes it (`x`, `y`, `z` then in the frame of C).
  bool side_move(bool rapid, double& x, double& y, double& z, int line);
  bool side_holes() const { return m_.milling.cross_holes == "side_cycle"; }
  /// A feed move with the tool across the spindle axis (milling on the diameter): a cut on the
  /// cylinder written in cylindrical interpolation (milling.cylindrical_on), or a plunge or
  /// retract along the radius. True when linear() writes it (a plunge outside the mode, `x`,
  /// `y`, `z` then in the turned frame); false when written here or refused.
  bool cylinder_feed(double& x, double& y, double& z, int line);
  /// Cylindrical interpolation on at `radius` (mm), C unclamped; off again (G7.1 C0).
  void enter_cylinder(double radius);
  void leave_cylinder();
  /// The head's tool length offset words due in the first move after indexing.
  void add_offset_words(text_buffer& b);
  /// Before a tilted tool's move on a mill/turn head (multi-axis writer): the spindle held as
  /// C, polar and the turned frame ended, B and C unclamped; false with the error.
  bool millturn_to_multiaxis(int line);
  // Multi-axis output (machining/channel_multiaxis.cpp), on a channel whose machine gives it a
  // kinematic chain ([[kinematics]]): every GOTO solved by kin::inverse, feed moves of joints
  // output linearised, every written point checked by the forward transform.
  /// A GOTO (rapid or feed) to CL point `p` under the tool axis in force.
  void multiaxis_move(bool rapid, const vec3& p, int line);
  /// Whether the multi-axis writer takes the next move: always (chain `moves = "all"`), or
  /// under a tool axis off the tool direction, with a rotary axis off 0 or in a tilted plane
  /// (`moves = "tilted"`). Handing a move back to the 3-axis writer ends G93 first.
  bool multiaxis_takes();
  /// Writes one point: the joints `j` rounded as the control reads them must give back
  /// `pose` (mm, part frame) by the forward transform; `inverse_f` > 0 writes G93 F<it>.
  bool write_point(bool rapid, const kin::joint_values& j, const kin::tool_pose& pose, double inverse_f,
                   int line);
  /// Before a rapid to `j` (linear words `nc`) that turns a rotary axis, or the first from the
  /// tool-change position or with the length offset (`force`: every word): the approach axis up
  /// first if the point is higher, the rotary axes alone, then the two other linear axes; the
  /// rapid itself then brings the tool down. Returns whether it wrote a block.
  bool reposition_rotaries(const kin::joint_values& j, const kin::tool_pose& pose, const double nc[3],
                           bool force);
  /// Before a feed move from a point with the tool along the outer rotary axis (the pole,
  /// where that axis's angle was kept) to one off it that needs the outer axis elsewhere:
  /// turns the outer axis first, with the tool where it is (`at`). The move then tilts the
  /// tool in the plane the CL gives instead of sweeping it round while it cuts. False (with
  /// the error) when a written point fails.
  bool turn_at_pole(const kin::tool_pose& at, const kin::tool_pose& to, double length, int line);
  // Looking ahead at the pole (machining/channel_pole.cpp): a RAPID to a point with the tool
  // along the outer rotary axis, whose angle is free there, is held with the records after it
  // (feeds, comments, more points on the pole) until the first point off the pole; the rapid
  // then takes that point's outer angle, so the axis turns in the rapid, not while the tool
  // cuts. Anything else, a wait or the end releases them as they came.
  /// Whether `e` was held (true) or is the caller's to process; releases what was held first.
  bool hold_for_pole(const event& e, bool both);
  /// Processes the held records; a held rapid on the pole takes `outer` as its outer angle.
  void release_held(std::optional<double> outer);
  /// Whether the unit-or-not `axis` lies along the chain's outer rotary axis.
  bool on_outer_pole(const vec3& axis) const;
  /// The outer angle of the point `pos` (CL units) under `axis`, solved from where the machine
  /// is; nullopt when it cannot be solved here (the move itself will say why).
  std::optional<double> pole_target(const vec3& pos, const vec3& axis) const;
  /// False (with the error) when the solution changes branch between `from` and `to` in a cut.
  bool same_branch(const kin::joint_values& from, const kin::joint_values& to, int line);
  /// The gauge length of the tool in the spindle for joints output; false with the error
  /// (naming the tool) when the CL's and the tool table's lengths differ. A length neither
  /// gives is no error yet: the moves post as long as no head tilts the tool (`length_free_`).
  bool tool_length_known(int line);
  /// With the length unknown: false (with the error naming the tool, once per tool) when the
  /// head values `read` (as the control reads them) tilt the tool.
  bool untilted_without_length(const kin::joint_values& read, int line);
  bool pivot_length_fits(std::optional<double> table, int line);
  bool upright();
  double head_turn_dip(const kin::joint_values& j, const kin::tool_pose& pose, const double factor[3]);
  /// How far (mm) the tip would move in the part, other than straight up the tool, if the
  /// rotary axes turned to `j`'s with the linear axes where the words left them (joints and
  /// pivot output); 0 when not known.
  double turn_sweep(const kin::joint_values& j, const double factor[3]);
  /// TLDATA/MILL's length (NX: diameter, lower radius, length, ...) for the next or this tool.
  void tool_data_length(const tool_data_event& t, bool after_call);
  /// A tool call on a chain channel: the new tool's offset register and length.
  void multiaxis_tool(const tool_event& t, int line);
  // 3+2 work (machining/channel_plane.cpp), on a chain with `plane` (G68.2).
  /// True when the GOTO to `pose` was taken by the tilted working plane: written in the open
  /// plane, or a plane opened for it, or an error; false: a multi-axis move as usual.
  bool plane_move(bool rapid, const kin::tool_pose& pose, int line);
  /// One point in the open plane: X Y Z in its frame, checked through its rotation.
  void plane_point(bool rapid, const kin::tool_pose& pose, int line);
  /// G69: the plane is cancelled.
  void close_plane();
  /// Looking ahead on a chain (the pole, channel_pole.cpp, and the plane): whether `e` was
  /// held (true) or is the caller's to process. A RAPID that would open a tilted working plane
  /// is held with the records after it until the cut shows what it is: feed moves (or arcs)
  /// under its axis up to a RAPID to another axis, a tool change, a frame or `max_plane_held`
  /// records make it 3+2 work (a plane); a feed move that turns the tool makes it simultaneous,
  /// and rapids alone position (no plane either: the chain's `output`).
  bool hold_multiaxis(const event& e, bool both);
  /// Whether `e` may be held (a rapid GOTO, or a record after held ones): the look-ahead is
  /// asked about these only, so a feed move costs it one test.
  bool may_hold(const event& e) const {
    if (!held_.empty() || !plane_held_.empty()) return true;
    const auto* m = std::get_if<motion_event>(&e.data);
    return m && m->rapid;
  }
  struct held_record;
  /// `e` to hold (at the pole or for the plane), with its CL line.
  held_record held_of(const event& e, bool both) const;
  /// Processes the records held for the plane; `plane` is what the cut showed.
  void release_plane_held(bool plane);
  /// Before a plane is set or cancelled: a waiting G40 goes out on its own; false (with the
  /// error) when the CL's cutter compensation is still on.
  bool plane_comp_off(int line);
  /// `v` (a point or direction of the part frame) in the open plane's frame.
  vec3 to_plane(const vec3& v) const;
  /// A point or offset of the plane's frame (mm) as the control reads it after writing it
  /// with the axes' decimals, turned back into the part frame.
  vec3 plane_written(const vec3& v) const;
  /// True when the tool axis in force is tilted and no plane is open for it: a hole there
  /// opens one with the rapid to its retract plane.
  bool plane_due() const;
  /// An arc or a drilling cycle in the open plane: true when the tool stands along the
  /// plane's Z (its G17); false with the error.
  bool plane_takes(int line);
  /// The CL arc `cl` in the open plane's frame (start, end, centre, axis).
  arc_event plane_arc(const arc_event& cl) const;
  /// The written end and centre of arc `w` (in the plane) taken back through the plane's
  /// rotation: false with the error when either misses the CL's `cl` by more than the tolerance.
  bool plane_arc_checked(const arc_event& cl, const arc_event& w, int line);
  /// Before a tool call and at the end: G94 again, and the length offset cancelled.
  void multiaxis_off();
  /// Before a tool call: the heads of the chain back at 0 if they may be tilted.
  void heads_upright();
  /// The header's plane again (G17 on a mill) when an arc left another in force: after a
  /// tool call, and before a canned cycle on a machine whose cycles name no plane.
  void restore_plane();
  /// At the end, a length-offset cancel still waiting for the home blocks: the footer's, when it
  /// homes and then cancels, else the home blocks and the cancel before the footer.
  void footer_cancels_length();
  /// An arc on a chain channel: only with the rotary axes at 0 and the tool along Z; G94
  /// again if G93 is in force. False after the error.
  bool multiaxis_arc(int line);
  /// A rapid that would start cutter compensation where the machine starts it only on a feed
  /// move (codes.cutcom_on_rapid = false): true with the error.
  bool comp_on_rapid_refused(bool rapid, int line) {
    if (!rapid || m_.codes.cutcom_on_rapid || !comp_starting()) return false;
    comp_on_rapid_error(line);
    return true;
  }
  void comp_on_rapid_error(int line);
  void error(int line, std::string message);
  /// The error for a word that does not fit the control's format (see machine::formats).
  void misfit(char address, double value);
  /// True when `v` written with `decimals` places fits the format of `address`; else reports.
  bool fits(char address, double v, int decimals);
  /// Checks the words of a block formatted from a template; reports the first misfit.
  bool block_fits(const std::string& block);
  /// Checks a DELAY's seconds against the format of the dwell template's address.
  bool dwell_fits(double seconds);
  /// Warns once per channel when a turret goes well past the spindle centre line.
  void check_side(double x_nc, double x_cl, int line);
  /// The last word written on one axis, for modal suppression.
  struct axis_memory {
    bool known = false;    ///< false after a tool change or home: the next word is written
    std::int64_t n = 0;    ///< the word's value in the last decimal place (12.346 -> 12346)
    double value = 0;      ///< the value it was rounded from
    std::int64_t max = 0;  ///< the largest count the control's format reads for this axis
    /// The axis's travel in counts (channel.axis min/max), for X only: a lathe's X is
    /// measured from the spindle centre in the program and on the machine alike.
    std::int64_t lo = INT64_MIN, hi = INT64_MAX;
  };
  /// Appends " X12.5" to `out` unless `last` already holds that word (modal suppression)
  /// and `always` is off; returns whether it wrote the word.
  bool axis_word(text_buffer& out, char address, double value, axis_memory& last, bool always = false);
  /// Appends " A12.345" (`decimals` places: 3 for degrees, 6 for G43.5's I J K) unless `last`
  /// holds that value and `always` is off. `counted`: round_fixed()'s count of `value`, when
  /// the caller has it.
  bool rotary_word(text_buffer& out, char address, double value, axis_memory& last, int decimals, bool always,
                   const std::int64_t* counted = nullptr);
  void forget_axes() { last_x_.known = last_y_.known = last_z_.known = false; }
  void append_feed(text_buffer& out);
  /// The words of one arc block ending at `end` after the G codes already in arc_: the axes,
  /// I/J/K (from the arc's start) or R, the feed. False when a word cannot be written.
  bool arc_block(const arc_event& a, const vec3& end, int plane, double axis_sign, double mirror, int line);
  /// The feed word of a cut (modal), or the error when no feed is in force; then the check
  /// that the spindle turns (spindle_turning).
  void cut_feed(text_buffer& out, int line);
  /// A blank before the next word, unless it is the first of a block built in place.
  void separate(text_buffer& out) const {
    if (out.size() != word_start_) out += ' ';
  }
  double nc_x(double x_cl) const { return x_cl * scale_ * x_factor_ * side_; }
  /// Z (and Y) on a spindle whose CL Z runs against the machine's (spindle_def::reverse_z):
  /// a half turn about X, so the frame stays right-handed.
  double nc_y(double y_cl) const { return y_cl * scale_ * z_sign_; }
  double nc_z(double z_cl) const { return z_cl * scale_ * z_sign_; }
  /// True when this channel's X runs against the CL (a mirrored turret, not a BOTH copy).
  bool mirrored() const { return x_factor_ * side_ < 0; }
  /// True when the channel's frame turns the sense of rotation in plane `plane` (17, 18, 19)
  /// over: a mirrored X, a reversed Z (the sub spindle), not both. G2/G3 swap there, and so
  /// do G41/G42 (the tool's left of the path becomes its right): one rule for both.
  bool sense_reversed(int plane) const;
  /// Writes the feed-mode code (G99/G98 or G95/G94) when it changes.
  void feed_mode(bool per_rev);

  const machine& m_;
  const channel_def& ch_;
  write_observer* observer_ = nullptr;
  bool observed_head_ = false;  // the head's lines shown to observer_
  bool observe_lines_ = false;  // observer_ wants every line
  diagnostic_sink& diags_;
  std::string cl_file_;
  block_writer out_;
  number_style axis_style_;
  double scale_ = 1.0;       // CL units -> output units (mm or inch)
  double cl_mm_ = 1.0;       // CL units -> mm
  double out_per_mm_ = 1.0;  // mm -> output units (1/25.4 in inch output)
  /// Decimals of the F word: 4 per revolution and 1 per minute in mm, 5 and 2 in inch.
  int feed_decimals(bool per_rev) const { return (per_rev ? 4 : 1) + (out_per_mm_ < 1 ? 1 : 0); }
  /// A feed (output units) above 0 that stays above 0 written, and fits the F word; else an
  /// error at `line`, naming `record` (a control alarms on F0 or a negative F).
  bool feed_writable(double value, bool per_rev, std::string_view record, int line);
  double x_factor_ = 2.0;    // diameter (2) or radius (1), negative when mirrored
  double side_ = 1.0;        // -1 while a HEAD/BOTH copy runs on the opposite side
  bool x_mirror_ = false;    // the channel's X axis is mirrored (a lower turret)
  bool x_diameter_ = false;  // and programmed in diameter (a lathe's)
  bool has_y_ = false;
  bool has_c_ = false;      // the channel has a C axis (mill/turn)
  bool c_mode_ = false;     // the workpiece spindle is held as the C axis
  bool c_clamped_ = false;  // and clamped (spindle.c_clamp)
  bool polar_ = false;      // polar interpolation is on

  bool side_hole_ = false;      // that cross hole is drilled with the side cycles (G87/G88)
  bool radial_ok_ = false;      // a cross hole is being written: its points are in the turned frame
  bool plane_hole_ = false;     // a hole in a tilted working plane: its points are in the plane's frame
  bool radial_frame_ = false;   // the frame is turned for cross holes (milling.radial_frame_on)
  bool cylinder_ = false;       // cylindrical interpolation is on (milling.cylindrical_on)
  double cylinder_r_ = 0;       // its radius (mm): the tip's on every cut
  double cylinder_c_ = 0;       // the C written last in it, continuous (no wrap at 360)
  bool cylinder_comp_ = false;  // G41/G42 started in it and not yet ended
  std::pair<std::int64_t, std::int64_t> saved_x_limits_{INT64_MIN, INT64_MAX};
  std::string pending_offset_;        // head_index.offset_* for the next move
  std::string length_offset_text_;    // channel.length_offset as the last tool call wrote it
  bool home_cancels_length_ = false;  // a block of codes.home cancels the length offset (G49, D0)
  bool length_lost_ = false;          // home cancelled the control's own offset, which no code gives back
  // A coolant-on block held from the tool call until the indexing head is indexed for the tool
  // (written then, before the approach): no coolant while the head turns (issue 37, item 10).
  std::string coolant_due_;
  // A user block of the event being written gave G91 (where the safe start writes G90): the
  // next user blocks' X are increments until the post's G90 after the event (restore_modes_after).
  bool user_incremental_ = false;
  // The X the event's user blocks left, when the post knew it before them: their G codes make the
  // post forget its axes (to write them all again), not where X is (the gate's increments).
  std::optional<double> user_x_;
  /// Writes coolant_due_, if any.
  void write_coolant_due() {
    if (coolant_due_.empty()) return;
    coolant_block(coolant_due_, false);
    coolant_due_.clear();
  }
  bool after_index_ = false;          // a tool was called: its offset words are due
  std::string head_offset_chosen_;    // the head's offset code index_head gave this tool
  double c_cos_ = 1, c_sin_ = 0;      // of the C angle in force
  std::optional<double> head_angle_;  // the indexing head's angle, once written
  double cl_clamp_ = 0;               // the speed clamp of the CL's last SPINDL under CSS (rpm); 0: none yet
  bool axes_free_ = false;            // B and C unclamped for tilted (multi-axis) moves
  const spindle_def* spindle_ = nullptr;   // the spindle SPINDL codes go to (workpiece or live)
  const spindle_def* work_ = nullptr;      // the workpiece spindle the channel works on (main, sub)
  double z_sign_ = 1.0;                    // -1 on a spindle with reverse_z
  bool offset_due_ = false;                // the work spindle's offset goes out after the first tool call
  const spindle_def* selected_ = nullptr;  // the spindle whose select code (M901/M902) went out last
  /// The tool's kind from TLDATA: what the workpiece spindle or the live one is for.
  enum class tool_kind : unsigned char { unknown, turn, mill, drill };
  tool_kind kind_ = tool_kind::unknown;       // of the tool in the spindle
  tool_kind next_kind_ = tool_kind::unknown;  // a TLDATA before the next tool call
  bool homed_ = false;                        // at home: no move since the home blocks
  bool length_cancel_due_ = false;            // the length offset's cancel waits for the home blocks
  bool after_call_ = false;                   // the last record that wrote anything was a tool call
  int tool_line_ = 0;                         // the CL line of the last tool call
  std::string tool_word_;                     // its major word (LOADTL, TURRET ...)
  int motion_g_ = -1;                         // last G0/G1/G2/G3
  int plane_ = 18;                            // G17/G18/G19 in force (lathe headers set G18)
  int header_plane_ = 0;                      // the header's G17/G18/G19, 0: it sets none
  axis_memory last_x_, last_y_, last_z_;      // axis words written last
  axis_memory last_c_;                        // the C word written last (degrees)
  std::string feed_g_;                        // G99/G98 (G95/G94) in force
  // The feed mode a dwell written under feed per minute left (G99): written again before the
  // next record that is no feed and no dwell, unless a FEDRAT sets a mode first or the program
  // ends (review 40: no G94/G95/G94 around a dwell, no G95 before M30).
  std::string feed_back_;
  bool absolute_code_ = false;  // the safe start writes G90 (absolute, not a lathe cycle)
  std::string last_f_;
  text_buffer arc_;  // the block being built, reused (arcs; moves are built in place)
  std::size_t word_start_ = std::string::npos;  // where a block built in place begins
  std::string feed_text_;                       // feed_value_ formatted, for the mode in feed_text_per_rev_
  double feed_text_value_ = -1;
  bool feed_text_per_rev_ = false;
  bool per_rev_ = false;  // feed mode of the last FEDRAT
  double feed_value_ = 0;
  std::optional<std::pair<double, bool>> fedrat_before_cycle_;  // a FEDRAT a cycle's feed replaced
  std::string pending_g_;                                       // G40/G41/G42 waiting for the next move
  bool comp_cl_on_ = false;  // the CL's CUTCOM/LEFT or RIGHT is in force (OFF not yet given)
  std::optional<cycle_event> cycle_;
  std::vector<std::string> end_home_;  // home blocks leave_cut(at_end) wrote (footer_in_force)
  bool in_cut_ = false;                // the CL's last move was a feed: the tool may be in the part (go_home)
  bool from_cut_ = false;              // in_cut_ before this motion record (a hole cycle's first point)
  // This tool's last rapid points since its call or the work spindle's change (retract_facing:
  // the levels it stood at clear of the part, above the point it stands at), and how many.
  std::array<vec3, 64> clear_at_{};
  std::size_t clear_n_ = 0;
  std::uint64_t left_blocks_ = 0;          // leave_cut() wrote these home blocks (bit i: block i)
  int cycle_line_ = 0;                     ///< the CL line of the cycle in force
  std::optional<thread_event> threading_;  ///< THREAD/TURN in force
  bool thread_saved_per_rev_ = false;      ///< the feed mode to restore at THREAD/OFF
  bool thread_saved_mode_ = false;         ///< whether a feed mode was written before THREAD/TURN
  bool cycle_refused_ = false;  ///< the cycle in force was refused (an error): its points write nothing
  vec3 pos_;                    // last CL point of this channel
  vec3 axis_{0, 0, 1};          // tool axis, from GOTO i,j,k or TLAXIS
  /// NX MSYS's rotation: the columns (the MCS's X, Y, Z in the absolute frame); unset when it is
  /// the identity.
  std::optional<std::array<vec3, 3>> msys_;
  int msys_line_ = 0;
  std::optional<std::vector<double>> first_msys_;  ///< the job's first MSYS: its MCS is the work offset
  int first_msys_line_ = 0;
  cl_frame frame_ = m_.program.frame;  ///< MSYS: the CL's MCS, or turned into the absolute frame
  vec3 cl_axis_{0, 0, 1};              ///< under MSYS: the tool axis in force, in the CL's (MCS) frame
  std::optional<vec3> csys_axis_;      ///< a turned SolidWorks CSYS's Z: the tool axis of its moves
  int csys_line_ = 0;
  bool csys_refused_ = false;                ///< the error for a move under another axis was given
  std::optional<vec3> refused_axis_;         // the tool axis tool_along_z last refused
  std::vector<std::string> restart_blocks_;  ///< the blocks that started the spindle now turning
  /// The last SPINDL that set a speed: SPINDL/ON turns the spindle on again with it (APT: the
  /// last speed, mode and direction), also after SPINDL/OFF.
  std::optional<spindle_event> last_speed_;
  /// A block that commands the spindle: not written by a balance cut's copy (set_balance_master).
  /// `stop`: the block stops it (it stays in force for footer_in_force until the next one).
  void spindle_block(const std::string& b, bool stop = false) {
    if (balance_copy_) return;
    out_.block(b);
    spindle_ended_ = stop ? b : std::string();
  }
  /// A coolant block; `off`: it turns the coolant off (in force for footer_in_force until the
  /// next coolant block).
  void coolant_block(const std::string& b, bool off) {
    out_.block(b);
    coolant_ended_ = off ? b : std::string();
  }
  /// The spindle stop and coolant off blocks this channel wrote last and that are still in
  /// force (nothing turned them on again, no AUXFUN or INSERT since): the footer need not
  /// write them a second time.
  std::string spindle_ended_, coolant_ended_;
  const channel_writer* balance_master_ = nullptr;
  job_spindles* job_spindles_ = nullptr;
  /// A cut on a shared spindle this channel had not started: an error at finish() when no
  /// channel starts that spindle anywhere in the job.
  struct unstarted_cut {
    std::size_t spindle = 0;
    int line = 0, column = 0;
    std::string source;  ///< the CL line, quoted in the error
  };
  std::vector<unstarted_cut> unstarted_;
  /// The cuts since the last spindle or tool record have been judged (one report a stretch).
  bool unstarted_judged_ = false;
  bool unstarted_ok_ = true;  ///< and what was found
  int errors_ = 0;            ///< errors this writer reported
  /// Tool diameters (mm) from TLDATA/MILL or CUTTER: of the tool in the spindle, of the next.
  std::optional<double> diameter_, next_diameter_;
  /// The tool in the spindle has a [[tool]] speed and the CL gave no SPINDL since its call.
  bool table_speed_due_ = false;
  /// After a hole: the retract plane the tool stands on, and the hole's CL point (pos_ then).
  std::optional<vec3> hole_exit_;
  /// The C angle of the hole cycle_point works on, turned to by to_hole: at the higher of the
  /// two holes' retract planes, not in the last hole's (attack 50: C swung the drill through
  /// the step between two faces, then turned back to climb).
  std::optional<double> c_hole_deg_;
  vec3 hole_point_{};
  bool at_pos_ = false;    ///< the tool stands at pos_ (a GOTO or an arc brought it there)
  bool cl_moved_ = false;  ///< the CL has moved the channel (a first MSYS after moves is a second MCS)
  /// Tool lengths (mm) from TLDATA/MILL or DRILL: the deepest hole the tool can drill.
  std::optional<double> reach_, next_reach_;
  std::map<int, double> reach_of_;  ///< the TLDATA length each tool number was given
  bool reach_from_table_ = false;   ///< reach_ is the [[tool]] length (shorter than TLDATA's)
  /// The rpm a surface speed gives a rotating tool of the machine's tool or the CL's diameter;
  /// nullopt after the error.
  std::optional<double> tool_rpm(const spindle_event& s, const spindle_def& sp, int line);
  bool balance_copy_ = false;  ///< the event being written is the copy of a HEAD/BOTH section
  /// The spindle was stopped for a tool change: restart_blocks_ go out again before the next
  /// move unless a SPINDL comes first.
  bool spindle_held_ = false;
  bool spindle_kept_ = false;  // a shared workpiece spindle kept turning through the tool change
  // The spindle turned on through the tool call (a turret's index, a kept shared spindle): its
  // speed and direction are written again before the new tool's first move, where the CL gives
  // no SPINDL, so that a restart at the tool call finds them (machinist's review 49, M4: the
  // Fusion Integrex post's onSection writes S and M3 at every tool).
  bool restate_spindle_ = false;
  // A transfer's blocks since the channel's last SPINDL: they synchronise and start the
  // spindles (M213), and a speed said again under the synchronisation would be the channel's
  // old one, not theirs: not restated until the CL gives SPINDL.
  bool transfer_since_speed_ = false;
  // The coolant block a tool call holds back until the speed is said again (the spindle
  // first, as at the first call), and writes it: after resume_spindle or the CL's SPINDL.
  std::string coolant_after_speed_;
  // At home since on_wait sent the channel there before its first tool call, with nothing
  // written since that may have moved it (a user block, INSERT text, an AUXFUN, a transfer's
  // blocks): the first tool call then need not home again (helper 40: an INSERT/G0 W-250.
  // before the first TURRET had the turret index where the text left it).
  bool start_home_ = false;
  void coolant_after_speed();
  /// The spindle this channel's SPINDL/OFF stopped, until a speed is given again.
  const spindle_def* stopped_by_cl_ = nullptr;
  /// The spindle a user block ([events], the script) stopped with its stop code, until the
  /// post or a user block starts it again; `user_stop_` the block.
  const spindle_def* stopped_by_user_ = nullptr;
  std::string user_stop_;
  std::string coolant_block_;      ///< the coolant-on block in force, "" when off
  std::string coolant_off_block_;  ///< the off block of the coolant kind in force
  int tool_ = -1;
  std::optional<int> start_tool_;                ///< post --tool: the tool in the spindle at the start
  tool_kind default_kind_ = tool_kind::unknown;  ///< post --tool-kind
  std::string cam_tool_;                         ///< the CAM's name of its tool (TOOL PATH, TPRINT)
  int cam_tool_line_ = 0;                        ///< the line that gave it
  std::string cam_tool_record_;                  ///< its major word
  std::string tool_cam_name_;  ///< the CAM's name in force when the tool in the spindle was taken
  int tool_cam_line_ = 0;      ///< the line that gave that name
  bool no_tool_said_ = false;  ///< the error for a move with no tool was given
  /// A CAM name came since the last tool call: the tool it names is called before the next
  /// record that needs one, unless a tool call record comes first.
  bool cam_tool_due_ = false;
  std::string tool_call_;  ///< the last tool call written (an offset change writes a new one)
  int waits_ = 0;
  std::vector<int> wait_cl_lines_;
  std::vector<noted_block> noted_;
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> block_cl_{nullptr, &std::fclose};  ///< block_cl_line()
  std::size_t block_cl_count_ = 0;                                                   // all of them
  std::size_t block_cl_in_file_ = 0;                                                 // those in the file
  std::vector<std::int32_t> block_cl_mem_;                                           // the others
  bool block_cl_failed_ = false;                                                     // no file: all in memory
  std::vector<std::size_t> wait_block_;                                              ///< wait_block_indices()
  bool note_every_block_ = false;
  bool cut_due_ = true;                     ///< the next G1/G2/G3 line is noted
  bool plain_block_ = false;                ///< the block being ended has no G, M or S word
  const kinematic_chain* chain_ = nullptr;  ///< this channel's chain, or nullptr (3-axis)
  const kin_lookahead* ahead_ = nullptr;    ///< its moves worked out ahead, or nullptr
  bool chain_heads_ = false;                ///< a rotary axis of it turns the tool (the length matters)
  unsigned tilting_heads_ = 0;              ///< bit i: rotary i is a head not along the tool (it tilts it)
  kin::joint_values joints_{};              ///< where the machine is (mm, degrees)
  kin::tool_pose pose_mm_{};                ///< the last CL pose, in mm
  bool pose_known_ = false;                 ///< false until the first GOTO (or FROM)
  std::optional<vec3> last_cl_tip_;         ///< the tip of the last GOTO on the chain (mm, part frame)
  std::optional<vec3> approach_from_;       ///< the one before it: where the move being written starts
  /// The highest the CL has put the tip (along the tool direction, mm) since the tool call: the
  /// CAM's clearance, where its approach came down from.
  double clear_height_ = -std::numeric_limits<double>::infinity();
  bool turn_clear_ = true;                            ///< the move being written starts or ends that high
  std::optional<double> length_cl_, next_length_cl_;  ///< TLDATA's length (mm) of the tool, of the next
  double tool_length_ = 0;                            ///< the length in use (mm)
  /// A record held (at the pole, or until a cut shows 3+2 or not), with its CL line for its
  /// errors: the reader has moved on when it is written.
  struct held_record {
    event e;
    bool both = false;
    std::string source;
  };
  std::vector<held_record> held_;             ///< records held at the pole
  vec3 held_axis_{};                          ///< the tool axis in force after them
  std::vector<held_record> plane_held_;       ///< records held for the plane
  const std::string* held_source_ = nullptr;  ///< the CL line of the held record being written
  vec3 plane_held_axis_{};                    ///< the tool axis of the rapid that began them
  bool plane_veto_ = false;                   ///< the released cut turns the tool: its rapid opens no plane
  bool plane_held_cut_ = false;               ///< a feed move or an arc under the held axis came
  std::optional<double> pole_hint_;           ///< the outer angle the held rapid takes
  bool length_known_ = false;
  bool length_refused_ = false;  ///< the tool's length error was reported
  /// The tool's length is unknown and the moves are posted while no head tilts the tool (the
  /// joints do not depend on the length there); the first point that tilts it is refused.
  bool length_free_ = false;
  int offset_ = 0;             ///< the tool's offset register (H)
  bool offset_on_ = false;     ///< G43 / G43.4 / G43.5 written for the tool in the spindle
  bool inverse_time_ = false;  ///< G93 in force
  axis_memory last_rot_[2], last_ijk_[3];
  kin::linearise_result lin_;  ///< reused by every feed move
  bool plane_on_ = false;      ///< a tilted working plane (G68.2) is in force
  vec3 plane_frame_[3];        ///< its X, Y, Z in the part frame, from the angles as written
  vec3 plane_axis_;            ///< the CL tool axis it was opened for
  void note_line(std::string_view line);
  /// The head's lines to the observer, once, when they are written (note_line, a record).
  void observe_head();
  bool warned_side_ = false;
  /// *chain_'s plan (kinematics/chain.hpp), made at its first move: plan() gives it.
  kin::chain_plan plan_;
  const kin::chain_plan& plan();
  /// The largest count of an inverse-time F word (G93), taken from the word format at the
  /// first one (0 until then): fits('F', ...) finds it twice at every block.
  std::int64_t inverse_f_max_ = 0;
  // [events] (machining/channel_events.cpp). ev_ is null when the machine file has none: the
  // post's own events then cost one pointer test each, and nothing else changes.
  const event_templates* ev_ = nullptr;
  bool program_started_ = false;  ///< events.program_start went out
  std::string user_cycle_;        ///< the type of the cycle whose events.cycle `before` went out
  /// The blocks of event `p` (`after` or before the post's own), formatted with `a` (its
  /// channel is set here), each held to the control's word formats like the post's own.
  void user_blocks(event_point p, bool after, template_args a);
  /// After the user's blocks of one event: the channel's own feed mode, plane and absolute mode
  /// back on where one of the blocks changed them; a block in the other unit system is an error
  /// (machining/channel_user_modes.cpp).
  void restore_modes_after(const std::vector<std::string>& blocks, std::string_view where);
  struct mode_change {
    bool feed = false, plane = false, incremental = false;
  };
  /// What `blocks` change of the channel's modes; false after the error of a unit change.
  bool modes_changed_by(const std::vector<std::string>& blocks, std::string_view where, mode_change& c);
  /// For on_block's replacement, which no later block of the post's follows to restore the
  /// modes: false, after the error, when it changes one.
  bool refuse_mode_changes(const std::string& block, std::string_view where);
  /// What `replacement` leaves out of the post's `block`: a mode code the post restores (G90,
  /// G91, the feed modes, the planes, the units) or an axis word as written, as "G90" or "the
  /// word X20."; "" when it keeps them all (machining/channel_user_modes.cpp).
  std::string lost_words(std::string_view block, std::string_view replacement) const;
  /// The blocks post.emit wrote in the script call running (restore_modes_after them).
  std::vector<std::string> script_emitted_;
  // A frame block's answers (frame_block), and where post.emit writes while one is asked.
  struct frame_edit {
    std::string in;
    bool header = false;
    std::size_t index = 0;  // of the block among the machine file's header or footer
    std::vector<std::string> out;
  };
  std::vector<frame_edit> frame_edits_;
  std::vector<std::string>* frame_out_ = nullptr;
  const char* block_part_ = "body";  // on_block's ctx.part
  /// events.program_start, once, before the channel's first block.
  void user_program_start();
  /// A record the machine file turns into blocks ([[events.record]]).
  void user_record(const passthrough_event& r, int line);
  /// Writes one user block: formatted, word formats checked, its wait codes noted for the
  /// self-check's findings, the modal state it may change forgotten.
  /// `where` names the template in errors (events.tool_change.after).
  void user_block(const std::string& tpl, const template_args& a, std::string_view where);
  /// {x} {y} {z} into `a`: the last position the program commanded (none before a move).
  void position_args(template_args& a) const;
  /// False, with the error at the CL record, when `tpl` names an axis `a` has no value for
  /// (no move yet; {y} on a channel without Y).
  bool position_given(std::string_view tpl, const template_args& a, std::string_view where);
  /// events.section (docs/customising.md): before a move, the section in force ends when the
  /// workpiece spindle or (at a rapid) the tool axis changed, and one opens when none is.
  void section_at_move(bool rapid, int line);
  /// motion() and arc() on a machine with [events]: section_at_move first.
  void user_motion(const motion_event& m, int line);
  void user_arc(const arc_event& a, int line);
  /// events.section.after, when a section is open: at a tool change, an operation start, the
  /// program's end, or before the next section.
  void section_end();
  /// events.operation around an operation record's comment; `before` ends the section.
  void user_operation(const text_event& d, bool after);
  bool moved_ = false;                         ///< a move has gone out: {x} {y} {z} have values
  bool sections_ = false;                      ///< the machine has events.section blocks
  bool section_open_ = false;                  ///< events.section.before went out, .after not yet
  const spindle_def* section_work_ = nullptr;  ///< the section's workpiece spindle
  vec3 section_axis_;                          ///< its tool axis
  template_args section_args_;                 ///< its tool, offset and operation
  int tool_offset_ = 0;                        ///< the offset of the tool call in force
  std::string op_name_;                        ///< the operation in force (TOOL PATH, OPFEATSTART)
  /// Whether user block `b` ([events], post.emit, on_block's) may be written: its words fit
  /// the control's formats, no blank splits a word, its X words are within the channel's X
  /// travel as the post's own are held (axis_word), it neither sets the coordinate system nor
  /// holds a program number (machining/channel_user_gate.cpp). Reports the first fault.
  /// `own`: the post's block that `b` replaces (on_block); a frame, length-offset or mode code
  /// it has is the post's own, not the user's.
  bool user_block_passes(const std::string& b, std::string_view own = {});
  /// INSERT text is the CAM user's NC, written as given; only a return to the reference
  /// position along a path the post cannot follow (G27, G29, G28/G30 through a point) stops the
  /// post at record `line` (machining/user_block_form.hpp, insert_return_error).
  bool insert_passes(const std::string& text, int line);
  /// False, with an error at CL line `line`, when `text` (`who` in the message) has a control
  /// character: one block must be one line (machining/channel_user_gate.cpp).
  bool text_is_one_line(std::string_view text, std::string_view who, int line);
  /// Whether user block `b` has an axis word outside its comments (X Y Z U V W A B C H): it may
  /// move the channel from where the post left it (machining/channel_events.cpp).
  bool names_an_axis(std::string_view b) const;
  /// The addresses that are increments whatever the mode: a lathe's U, V, W, H in G-code
  /// system A where the channel has no axis of that name.
  std::string increment_letters() const;
  /// The M codes of what the post does itself, with what each is: the spindles' chuck open, C
  /// axis clamp and unclamp, the indexing head's clamp and unclamp (refused in user blocks).
  std::vector<std::pair<long long, std::string>> reserved_m_codes() const;
  int line_ = 0, column_ = 0;  // the event being written: where its errors point
  // The script (machining/channel_script.cpp); null without one (then no script work at all).
  job_script* script_ = nullptr;
  /// Runs `call` (a hook) unless the script has failed; a script_error becomes the error at
  /// the script's line and a note at the CL record being posted.
  template <class F>
  void run_script(F&& call) {
    if (script_->failed) return;
    out_.begin();  // on_block sees the header's blocks before any the script writes
    try {
      call(*script_->lua);
    } catch (const scripting::script_error& e) {
      script_failed(e);
    }
  }
  void script_failed(const scripting::script_error& e);
  /// A note after the error for a block of the script's (`how`: post.emit, on_block).
  void script_block_note(std::string_view block, std::string_view how);
  scripting::script_context script_context() const;
  void script_program(bool start);
  void script_tool(int tool, int offset);
  void script_record(const passthrough_event& r, int line);
  /// After a hook other than on_block: restore_modes_after the blocks post.emit wrote in it.
  void restore_after_emits();
  // script_host and block_filter: post.emit, post.warning, on_block.
  bool emit(std::string_view block) override;
  void warning(std::string_view message) override;
  block_writer::verdict filter(std::string_view block, std::string& replacement) override;
  /// What a user block (template or script) does besides being written: its wait codes are
  /// counted (`waits`; count_waits_in), a G code makes the next move write its axes again, an
  /// M code may turn the spindle or the coolant on (note_user_m).
  void note_user_block(std::string_view b, bool waits);
  /// M`code` of a user block: which of the footer's spindle stop and coolant off it leaves in
  /// force (footer_in_force).
  void note_user_m(long long code);
  /// One wait block written at CL line `cl_line`: numbered for the self-check's findings
  /// (post/sync_at_cl), the interference rule's block index, the next cut noted.
  void count_wait(int cl_line);
  /// count_wait for each wait code in block `b` (outside comments), as the checker reads it.
  void count_waits_in(std::string_view b, int cl_line);
  /// The wait words of block `b` as the self-check reads them (outside comments).
  int wait_words_in(std::string_view b) const;
  /// Block `b`'s words as a control reads them (upper case, without comments; G00 as G0).
  std::vector<std::string> frame_words(std::string_view b) const;
  /// A header or footer block's reply to on_block: the first word of `block` it leaves out
  /// ("the word G54"; a G28 may be a G30), "" when it keeps them all; `kept`: and it adds M
  /// codes only.
  std::string frame_words_lost(std::string_view block, std::string_view reply, bool& kept) const;
  /// The first wait word of `b` in any case (`m101`), "" for none.
  std::string frame_waits(std::string_view b) const;
  /// block_filter: a block the filter saw went out as `block` (kept or replaced); its waits
  /// are counted here, the post's own as a replacement's (the writer then counts none itself).
  void block_written(std::string_view block, bool replaced) override;
  bool user_writing_ = false;  ///< user_block is writing its block (its waits: block_written)
  bool filtered_ = false;      ///< the script's on_block sees every block (use_script)
  /// The spindles a user block started (note_user_m): finish() stops those the footer does not.
  std::vector<const spindle_def*> user_spindles_;
  int wait_line_ = 0;         ///< the CL line of the wait block being written (on_wait)
  std::string program_name_;  ///< for ctx.program, asked for once
};

}  // namespace twinpost
