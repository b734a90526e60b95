#pragma once
// Where the channels of a post wait for each other, and the one table of its names
// (`--sync explicit|sequential|optimise|auto`, the post summary's "waits (explicit)").
#include <array>
#include <optional>
#include <string_view>

namespace twinpost {

/// explicit_marks: at the job's sync records; sequential: at every head switch;
/// optimise: where the wait schedule puts them for the shortest cycle (channels/wait_plan.hpp);
/// automatic: explicit when the job has sync records, else sequential.
enum class sync_policy { explicit_marks, sequential, optimise, automatic };

struct sync_policy_name {
  sync_policy policy;
  std::string_view name;
};

/// In the order messages list them.
inline constexpr std::array<sync_policy_name, 4> sync_policy_names{{
    {sync_policy::explicit_marks, "explicit"},
    {sync_policy::sequential, "sequential"},
    {sync_policy::optimise, "optimise"},
    {sync_policy::automatic, "auto"},
}};

constexpr std::string_view sync_policy_to_name(sync_policy p) {
  for (const sync_policy_name& n : sync_policy_names)
    if (n.policy == p) return n.name;
  return {};
}

constexpr std::optional<sync_policy> sync_policy_from_name(std::string_view name) {
  for (const sync_policy_name& n : sync_policy_names)
    if (n.name == name) return n.policy;
  return std::nullopt;
}

}  // namespace twinpost
