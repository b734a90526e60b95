// machines/machine_kinematics: the [[kinematics]] tables of a machine file, their defaults and
// their errors.
#include <catch2/catch.hpp>

#include "kinematics/chain.hpp"
#include "kinematics_test_support.hpp"
#include "machine_test_support.hpp"

using namespace twinpost;
using test::machine_error_of;

namespace {

// A machine with one channel (lines 1-8); line 9 on is the [[kinematics]] a test is about.
const std::string one_channel = test::machine_head + "[[channel]]\nnumber = 1\n" + test::xz_axes;

}  // namespace

TEST_CASE("a [[kinematics]] table gives the channel's chain, with defaults", "[kinematics][machines]") {
  const machine m = parse_machine(one_channel +
                                      "[[kinematics]]\n"
                                      "channel = 1\n"
                                      "[[kinematics.rotary]]\n"
                                      "address = \"B\"\n"
                                      "kind = \"head\"\n"
                                      "direction = [0, 2, 0]\n"
                                      "point = [1.5, 0, 300]\n"
                                      "min = -20\n"
                                      "max = 20.5\n"
                                      "prefer = \"positive\"\n"
                                      "[[kinematics.rotary]]\n"
                                      "address = \"C\"\n"
                                      "kind = \"table\"\n"
                                      "direction = [0, 0, -1]\n"
                                      "continuous = true\n"
                                      "rollover = \"shortest\"\n",
                                  "m.toml");
  REQUIRE(m.kinematics.size() == 1);
  const kinematic_chain& c = m.kinematics[0];
  CHECK(c.channel == 1);
  CHECK(c.linear == "XYZ");
  CHECK(c.tool_direction == vec3{0, 0, 1});
  CHECK(c.tolerance == 0.001);
  CHECK(c.angle_tolerance == 0.001);
  CHECK(c.output == multiaxis_output::joints);
  CHECK(c.tool_tip_on == "G43.4");
  CHECK(c.tool_tip_off == "G49");
  CHECK(c.length_on == "G43");
  CHECK(c.inverse_time == "G93");
  CHECK(c.chordal_tolerance == 0.01);
  CHECK(c.plane.empty());
  CHECK(c.moves == multiaxis_moves::all);
  CHECK(c.plane_index == "G53.1");
  CHECK(c.plane_off == "G69");
  REQUIRE(c.rotaries.size() == 2);
  CHECK(c.rotaries[0].address == 'B');
  CHECK(c.rotaries[0].kind == rotary_kind::head);
  CHECK(c.rotaries[0].direction == vec3{0, 1, 0});  // normalised
  CHECK(c.rotaries[0].point == vec3{1.5, 0, 300});
  CHECK(c.rotaries[0].min == -20.0);
  CHECK(c.rotaries[0].max == 20.5);
  CHECK(!c.rotaries[0].continuous());
  CHECK(c.rotaries[0].prefer == preferred_sign::positive);
  CHECK(c.rotaries[0].rollover == rotary_rollover::absolute);
  CHECK(c.rotaries[1].continuous());
  CHECK(c.rotaries[1].rollover == rotary_rollover::shortest);
  CHECK(c.rotaries[1].point == vec3{0, 0, 0});
  CHECK(kin::kind_of(c) == kin::chain_kind::head_table);
  // A machine without [[kinematics]] has no chain.
  CHECK(parse_machine(one_channel, "m.toml").kinematics.empty());
}

TEST_CASE("errors in [[kinematics]] are reported at their place", "[kinematics][machines]") {
  const std::string k = one_channel + "[[kinematics]]\nchannel = 1\n";  // lines 9-10
  const std::string b =
      k + "[[kinematics.rotary]]\naddress = \"B\"\nkind = \"head\"\ndirection = [0, 1, 0]\n";
  CHECK(machine_error_of(one_channel + "[[kinematics]]\nchannel = 2\n") ==
        "m.toml:10:11: error: kinematics.channel 2 names no channel");
  CHECK(machine_error_of(k + "[[kinematics]]\nchannel = 1\n") ==
        "m.toml:12:11: error: channel 1 has two [[kinematics]] tables");
  CHECK(machine_error_of(k + "linear = \"XYX\"\n") ==
        "m.toml:11:10: error: kinematics.linear must be three different letters (\"XYZ\"), not \"XYX\"");
  CHECK(machine_error_of(k + "tool_direction = [0, 0]\n") ==
        "m.toml:11:18: error: kinematics.tool_direction must be an array of three numbers [x, y, z]");
  CHECK(machine_error_of(k + "tool_direction = [0, 0, 0]\n") ==
        "m.toml:11:18: error: kinematics.tool_direction must not be the zero vector");
  CHECK(machine_error_of(k + "tolerance = 0\n") ==
        "m.toml:11:13: error: kinematics.tolerance must be > 0 and at most 1 (mm), not 0");
  CHECK(machine_error_of(k + "chordal_tolerance = -1\n") ==
        "m.toml:11:21: error: kinematics.chordal_tolerance must be > 0 and at most 1 (mm), not -1");
  CHECK(machine_error_of(k + "output = \"tcp\"\n") ==
        "m.toml:11:10: error: kinematics.output must be joints, tool_tip, vector or pivot, not 'tcp'");
  CHECK(machine_error_of(b) ==
        "m.toml:11:1: error: rotary axis B needs min and max (degrees), or continuous = true");
  CHECK(machine_error_of(b + "min = 10\nmax = -10\n") ==
        "m.toml:15:7: error: kinematics.rotary.min (10) must be <= kinematics.rotary.max (-10)");
  CHECK(machine_error_of(b + "min = 10\ncontinuous = true\n") ==
        "m.toml:16:14: error: kinematics.rotary.continuous = true takes no min or max");
  CHECK(machine_error_of(b + "continuous = true\nrollover = \"modulo\"\n") ==
        "m.toml:16:12: error: kinematics.rotary.rollover must be absolute or shortest, not 'modulo'");
  CHECK(machine_error_of(b + "min = 0\nmax = 1\nrollover = \"shortest\"\n") ==
        "m.toml:17:12: error: kinematics.rotary.rollover = \"shortest\" needs continuous = true");
  CHECK(machine_error_of(b + "continuous = true\nkind2 = 1\n") ==
        "m.toml:16:1: error: unknown key 'kinematics.rotary.kind2'");
  CHECK(machine_error_of(k + "[[kinematics.rotary]]\naddress = \"Y\"\n") ==
        "m.toml:12:11: error: kinematics.rotary.address Y is a linear axis of the chain");
  CHECK(machine_error_of(k + "[[kinematics.rotary]]\naddress = \"C\"\nkind = \"spindle\"\n") ==
        "m.toml:13:8: error: kinematics.rotary.kind must be head or table, not 'spindle'");
  const std::string c = b + "continuous = true\n[[kinematics.rotary]]\naddress = \"C\"\nkind = \"table\"\n";
  CHECK(machine_error_of(c + "direction = [0, 2, 0]\ncontinuous = true\n") ==
        "m.toml:16:1: error: rotary axes B and C are parallel: they cannot tilt the tool");
  // The head is the inner rotation of a head/table chain: along the tool it tilts nothing.
  CHECK(machine_error_of(k +
                         "[[kinematics.rotary]]\naddress = \"B\"\nkind = \"head\"\ndirection = [0, 0, 1]\n"
                         "continuous = true\n[[kinematics.rotary]]\naddress = \"C\"\nkind = \"table\"\n"
                         "direction = [1, 0, 0]\ncontinuous = true\n") ==
        "m.toml:16:1: error: rotary axis B lies along the tool: it cannot tilt it");
  CHECK(machine_error_of(
            c + "direction = [0, 0, 1]\ncontinuous = true\n[[kinematics.rotary]]\naddress = \"A\"\n") ==
        "m.toml:21:1: error: channel 1 has more than two rotary axes (the most twinpost solves)");
  CHECK(machine_error_of(c + "direction = [0, 0, 1]\ncontinuous = true\naddress2 = 1\n") ==
        "m.toml:21:1: error: unknown key 'kinematics.rotary.address2'");
}

TEST_CASE("pivot output and the rotary word order are read, and their errors reported at their place",
          "[kinematics][machines]") {
  const std::string k = one_channel + "[[kinematics]]\nchannel = 1\n";  // lines 9-10
  const std::string heads =
      "[[kinematics.rotary]]\naddress = \"C\"\nkind = \"head\"\ndirection = [0, 0, 1]\npoint = [0, 0, 20]\n"
      "min = -360\nmax = 360\n[[kinematics.rotary]]\naddress = \"A\"\nkind = \"head\"\n"
      "direction = [1, 0, 0]\npoint = [0, 0, 20]\nmin = -110\nmax = 110\n";
  const machine m = parse_machine(
      k + "output = \"pivot\"\nprogrammed_length = 150\nrotary_order = \"chain\"\n" + heads, "m.toml");
  const kinematic_chain& c = m.kinematics[0];
  CHECK(c.output == multiaxis_output::pivot);
  CHECK(c.programmed_length == 150);
  CHECK(c.rotary_order == rotary_word_order::chain);
  CHECK(c.length_on.empty());  // no length offset unless the machine names one
  CHECK(solves_joints(c));
  CHECK(offset_code(c).empty());
  // The pivot: 150 mm up the tool from the tip, then the outer head's point from the nose.
  CHECK(pivot_shift(c) == vec3{0, 0, 170});
  CHECK(rotary_words(c) == std::array<std::size_t, 2>{0, 1});  // C, then A
  // By address (the default): A before C.
  const machine by_address = parse_machine(k + heads, "m.toml");
  CHECK(rotary_words(by_address.kinematics[0]) == std::array<std::size_t, 2>{1, 0});
  CHECK(chosen_length(c, 100.0, 120.0) == 150.0);  // pivot output: the programmed length

  CHECK(machine_error_of(k + "output = \"pivot\"\n" + heads) ==
        "m.toml:9:1: error: kinematics.output = \"pivot\" needs programmed_length (mm): the tool length the "
        "pivot points are written for");
  CHECK(machine_error_of(k + "programmed_length = 150\n" + heads) ==
        "m.toml:11:21: error: kinematics.programmed_length is read only with output = \"pivot\"");
  CHECK(machine_error_of(k + "output = \"pivot\"\nprogrammed_length = 0\n" + heads) ==
        "m.toml:12:21: error: kinematics.programmed_length must be >= 1 and < 10000 (mm), not 0");
  CHECK(machine_error_of(k + "output = \"pivot\"\nprogrammed_length = 150\n"
                             "[[kinematics.rotary]]\naddress = \"C\"\nkind = \"table\"\n"
                             "direction = [0, 0, 1]\ncontinuous = true\n") ==
        "m.toml:11:10: error: kinematics.output = \"pivot\" needs a head: no pivot turns the tool (use "
        "\"joints\")");
  CHECK(
      machine_error_of(k + "output = \"pivot\"\nprogrammed_length = 150\nmoves = \"tilted\"\n" + heads) ==
      "m.toml:13:9: error: kinematics.output = \"pivot\" needs moves = \"all\": the lathe's moves write the "
      "tip, not the pivot");
  CHECK(machine_error_of(k + "output = \"pivot\"\nprogrammed_length = 150\nplane = \"G68.2\"\n" + heads) ==
        "m.toml:13:9: error: kinematics.output = \"pivot\" takes no plane: a tilted working plane positions "
        "the "
        "tip, not the pivot");
  CHECK(machine_error_of(k + "output = \"pivot\"\nprogrammed_length = 150\nlength_on = \"G43\"\n" + heads) ==
        "m.toml:13:13: error: kinematics.length_on = \"G43\" under pivot output: G43 applies the length "
        "along Z, "
        "and a tilted tool needs the length along the tool (Fanuc's G43.1, tool length compensation in the "
        "tool "
        "axis direction), or none");
  for (const std::string spelling : {"G043 H", "g43", "G49 G44.0"})
    CHECK(machine_error_of(k + "output = \"pivot\"\nprogrammed_length = 150\nlength_on = \"" + spelling +
                           "\"\n" + heads)
              .find("under pivot output: G") != std::string::npos);
  CHECK(
      machine_error_of(k + "output = \"pivot\"\nprogrammed_length = 150\nlength_on = \"G43.4\"\n" + heads) ==
      "m.toml:13:13: error: kinematics.length_on = \"G43.4\" under pivot output: G43.4 takes X Y Z as the "
      "tip, "
      "and a tilted tool needs the length along the tool (Fanuc's G43.1, tool length compensation in the "
      "tool "
      "axis direction), or none");
  // The pivot is where the axes cross, whichever points the file gives on them.
  const std::string apart =
      "[[kinematics.rotary]]\naddress = \"C\"\nkind = \"head\"\ndirection = [0, 0, 1]\n"
      "min = -360\nmax = 360\n[[kinematics.rotary]]\naddress = \"A\"\nkind = \"head\"\n"
      "direction = [1, 0, 0]\npoint = [0, 50, 100]\nmin = -110\nmax = 110\n";
  CHECK(machine_error_of(k + "output = \"pivot\"\nprogrammed_length = 150\n" + apart) ==
        "m.toml:11:10: error: kinematics.output = \"pivot\" needs the heads' axes to cross on the tool's "
        "axis: they "
        "pass each other (50 mm); the control positions that one point");
  std::string crossing = apart;
  crossing.replace(crossing.find("[0, 50, 100]"), 12, "[7, 0, 100]");  // on the A axis, 100 mm up
  CHECK(pivot_shift(parse_machine(k + "output = \"pivot\"\nprogrammed_length = 150\n" + crossing, "m.toml")
                        .kinematics[0]) == vec3{0, 0, 250});
  // Codes that would begin a block with a comment, a line break or a tape mark.
  CHECK(machine_error_of(k + "inverse_time = \"G93 ;\"\n" + heads) ==
        "m.toml:11:16: error: kinematics.inverse_time must hold codes only: ';' would make a comment of the "
        "block "
        "it begins");
  // A program end in a code the post writes mid-program (attack 44: inverse_time = "M30").
  CHECK(machine_error_of(k + "inverse_time = \"M30\"\n" + heads) ==
        "m.toml:11:16: error: kinematics.inverse_time \"M30\": M30 ends the program (M99 goes back to its "
        "start) there: only program.end_code and the footer may end it");
  // What the codes do (attack 45): inverse time is no per-minute or motion code, a joints
  // length code is a G43 (not its cancel, G44 or tool-tip control), blanks inside words count.
  // Whitelists (verify 46): inverse time holds G93, a joints length code G43, feed_per_min G94 or G98.
  CHECK(machine_error_of(k + "inverse_time = \"G98\"\n" + heads) ==
        "m.toml:11:16: error: kinematics.inverse_time \"G98\" holds no G93: it must be the inverse-time feed "
        "code alone (G93), the F of the moves after it 1/min");
  CHECK(
      machine_error_of(k + "length_on = \"G43.1\"\n" + heads) ==
      "m.toml:11:13: error: kinematics.length_on \"G43.1\" under joints output holds no G43: the joints are "
      "solved for the tool's length made up along Z by a length offset (G43)");
  CHECK(machine_error_of(k + "inverse_time = \"G93 {\"\n" + heads) ==
        "m.toml:11:16: error: kinematics.inverse_time must hold codes only: '{' would be written as it "
        "stands, no "
        "word of a block");
  CHECK(
      machine_error_of(k + "inverse_time = \"G94\"\n" + heads) ==
      "m.toml:11:16: error: kinematics.inverse_time \"G94\" holds G94: it must be the inverse-time feed code "
      "alone (G93), the F of the moves after it 1/min");
  CHECK(machine_error_of(k + "length_on = \"G49\"\n" + heads) ==
        "m.toml:11:13: error: kinematics.length_on \"G49\" under joints output holds G49: the joints are "
        "solved "
        "for the tool's length made up along Z by a length offset (G43)");
  CHECK(
      machine_error_of(k + "output = \"pivot\"\nprogrammed_length = 150\nlength_on = \"G 43\"\n" + heads) ==
      "m.toml:13:13: error: kinematics.length_on = \"G 43\" under pivot output: G43 applies the length along "
      "Z, and a tilted tool needs the length along the tool (Fanuc's G43.1, tool length compensation in the "
      "tool axis direction), or none");
  CHECK(machine_error_of(k + heads + "[codes]\nfeed_per_min = \"\"\n") ==
        "m.toml:26:16: error: codes.feed_per_min \"\" must end inverse time (G93): the feed moves after a "
        "turning move would keep reading F as 1/min");
  CHECK(machine_error_of(k + "inverse_time = \"\"\n" + heads) ==
        "m.toml:11:16: error: kinematics.inverse_time must name the inverse-time feed code (G93): joints and "
        "pivot "
        "output write F as 1/min on the moves that turn a rotary axis");
  CHECK(parse_machine(k + "output = \"pivot\"\nprogrammed_length = 150\nlength_on = \"G43.1\"\n" + heads,
                      "m.toml")
            .kinematics[0]
            .length_on == "G43.1");
  CHECK(machine_error_of(k + "rotary_order = \"ca\"\n" + heads) ==
        "m.toml:11:16: error: kinematics.rotary_order must be address or chain, not 'ca'");
}
