// twinpost kin: a channel's kinematic chain ([[kinematics]], docs/kinematics.md) asked for the
// joint values of CL points, each solved from the one before, optionally linearised.
#include <charconv>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "cli/cli_util.hpp"
#include "cli/command_table.hpp"
#include "cli/commands.hpp"
#include "cli/machine_dirs.hpp"
#include "kinematics/forward.hpp"
#include "kinematics/inverse.hpp"
#include "kinematics/linearise.hpp"

namespace twinpost::cli {

namespace {

std::string kin_usage() {
  return "usage: " + command_usage("kin") +
         "\n"
         "\n"
         "Prints the joint values of the channel's [[kinematics]] chain (docs/kinematics.md) for\n"
         "each CL point x,y,z or x,y,z,i,j,k (the tool axis; default the chain's tool direction),\n"
         "each solved from the one before: the first from the rotary values of --from (default\n"
         "0). --linearise T also prints the sub-moves (N.k) that keep the tip within T mm of the\n"
         "straight line from the point before. A point may start with '-'.\n"
         "\n"
         "options:\n"
         "  -m [ --machine ] M     built-in machine name or machine file (required)\n"
         "  --channel N            the channel whose chain is used (default 1)\n"
         "  --tool-length L        gauge point to tool tip, mm (default 0)\n"
         "  --from A[,B]           the rotary values before the first point, degrees\n"
         "  --linearise T          cut each move to a chordal tolerance of T mm\n"
         "  -h [ --help ]          show this help\n"
         "Exit status: 0 every point solved, 1 a point cannot be reached, 2 usage or configuration error.\n";
}

// Numbers separated by commas; nullopt unless there are `min`..`max` of them, each whole.
std::optional<std::vector<double>> numbers(const std::string& text, std::size_t min, std::size_t max) {
  std::vector<double> out;
  const char* p = text.data();
  const char* end = p + text.size();
  while (true) {
    double v = 0;
    const auto [next, ec] = std::from_chars(p, end, v);
    if (ec != std::errc() || !std::isfinite(v)) return std::nullopt;
    out.push_back(v);
    p = next;
    if (p == end) break;
    if (*p != ',') return std::nullopt;
    ++p;
  }
  if (out.size() < min || out.size() > max) return std::nullopt;
  return out;
}

std::string joints_text(const kinematic_chain& c, const kin::joint_values& j) {
  const double lin[3] = {j.linear.x, j.linear.y, j.linear.z};
  std::string s;
  for (int i = 0; i < 3; ++i) s += fmt::format("{}{}{}", i ? " " : "", c.linear[i], kin::number_text(lin[i]));
  for (std::size_t i = 0; i < c.rotaries.size(); ++i)
    s += fmt::format(" {}{}", c.rotaries[i].address, kin::number_text(j.rotary[i]));
  return s;
}

int usage_error(const std::string& message) {
  fmt::print(stderr, "twinpost kin: {}\n", message);
  return 2;
}

}  // namespace

int run_kin(const args& a) {
  std::string machine_name, from_text;
  int channel = 1;
  double tool_length = 0, tolerance = 0;
  std::vector<std::string> points;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const std::string& arg = a[i];
    if (arg == "--help" || arg == "-h") {
      std::fputs(kin_usage().c_str(), stdout);
      return 0;
    }
    const bool valued = arg == "--machine" || arg == "-m" || arg == "--channel" || arg == "--tool-length" ||
                        arg == "--from" || arg == "--linearise";
    if (!valued) {
      if (arg.starts_with("--"))
        return usage_error(fmt::format("unknown option '{}'\n\n{}", arg, kin_usage()));
      points.push_back(arg);
      continue;
    }
    if (i + 1 == a.size()) return usage_error(fmt::format("{} needs a value", arg));
    const std::string& v = a[++i];
    if (arg == "--machine" || arg == "-m") {
      machine_name = v;
    } else if (arg == "--from") {
      from_text = v;
    } else {
      const std::optional<std::vector<double>> n = numbers(v, 1, 1);
      if (!n) return usage_error(fmt::format("{} takes a number, not '{}'", arg, v));
      if (arg == "--channel" && ((*n)[0] != std::floor((*n)[0]) || (*n)[0] < 1 || (*n)[0] > 64))
        return usage_error(fmt::format("--channel takes a channel number, not '{}'", v));
      if (arg == "--channel") channel = static_cast<int>((*n)[0]);
      if (arg == "--tool-length") tool_length = (*n)[0];
      if (arg == "--linearise") tolerance = (*n)[0];
      if (arg == "--linearise" && !(tolerance > 0)) return usage_error("--linearise takes a tolerance > 0");
      if (arg == "--tool-length" && !(tool_length >= 0 && tool_length < 1e4))
        return usage_error(fmt::format("--tool-length takes a length from 0 to 10000 mm, not '{}'", v));
    }
  }
  if (machine_name.empty()) return usage_error("missing --machine");
  if (points.empty()) return usage_error("missing CL points (x,y,z or x,y,z,i,j,k)");

  const machine m = locate_machine(machine_name).def;  // a bad file throws: exit 2
  const kinematic_chain* chain = nullptr;
  for (const kinematic_chain& c : m.kinematics)
    if (c.channel == channel) chain = &c;
  if (!chain) {
    print_error(fmt::format("machine '{}' has no [[kinematics]] for channel {}", m.name, channel));
    return 2;
  }
  kin::joint_values previous;
  if (!from_text.empty()) {
    const std::optional<std::vector<double>> r =
        numbers(from_text, chain->rotaries.size(), chain->rotaries.size());
    if (!r)
      return usage_error(
          fmt::format("--from takes {} rotary value(s), not '{}'", chain->rotaries.size(), from_text));
    for (std::size_t i = 0; i < r->size(); ++i) previous.rotary[i] = (*r)[i];
  }
  std::optional<kin::tool_pose> last;
  for (std::size_t n = 0; n < points.size(); ++n) {
    const std::optional<std::vector<double>> v = numbers(points[n], 3, 6);
    if (!v || v->size() == 4 || v->size() == 5)
      return usage_error(fmt::format("point '{}' is not x,y,z or x,y,z,i,j,k", points[n]));
    kin::tool_pose pose{{(*v)[0], (*v)[1], (*v)[2]}, chain->tool_direction};
    if (v->size() == 6) pose.axis = {(*v)[3], (*v)[4], (*v)[5]};
    if (tolerance > 0 && last) {
      const kin::linearise_result r = kin::linearise(*chain, *last, previous, pose, tool_length, tolerance);
      if (!r.ok()) {
        print_error(fmt::format("point {}: {}", n + 1, r.message));
        return 1;
      }
      for (std::size_t k = 0; k + 1 < r.points.size(); ++k)
        fmt::print("{}.{}: {}\n", n + 1, k + 1, joints_text(*chain, r.points[k]));
      previous = r.points.back();
    } else {
      const kin::ik_result r = kin::inverse(*chain, pose, tool_length, previous);
      if (!r.ok()) {
        print_error(fmt::format("point {}: {}", n + 1, r.message));
        return 1;
      }
      previous = r.joints;
    }
    fmt::print("{}: {}\n", n + 1, joints_text(*chain, previous));
    last = pose;
  }
  return 0;
}

}  // namespace twinpost::cli
