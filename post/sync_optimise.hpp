#pragma once
// `--sync optimise` (issue 39, docs/wait-placement.md): the post places the waits of a
// two-channel job for the shortest cycle. The job is posted sequentially first (nothing
// written): that gives its operations (channels/wait_plan.hpp) and, from the block timer, each
// one's time. The schedule (channels/wait_schedule.hpp) then places the waits, the job is
// posted with them, and the post's own self-check (the wait check, the spindle rules, the
// turret interference rule) holds the programs as it holds any other. Each pair of operations
// a finding names keeps the CL's order from then on, and the job is posted again with the new
// schedule, until the programs check sound. When no new pair can be learned (a finding at no
// operation) or after a few posts, the job is posted sequentially, with a warning that says why.
#include <functional>

#include "channels/wait_plan.hpp"
#include "post/post_job.hpp"

namespace twinpost {

/// What one post of the job gives the optimiser.
struct optimise_attempt {
  post_summary sum;
  job_operations ops;
};

/// The posts the optimiser makes.
enum class optimise_step {
  timing,             ///< sequential, with a wait at every operation (each timed alone); nothing written
  planned,            ///< with the plan's waits; written when the programs check sound
  fallback,           ///< sequential, written
  fallback_explicit,  ///< the job's sync records alone (explicit), written: a job that has any
};

/// Posts the job once as `step` says (`plan`: the waits of a planned post); diagnostics to `diags`.
using post_attempt =
    std::function<optimise_attempt(optimise_step step, const job_operations* plan, diagnostic_sink& diags)>;

/// The most posts the optimiser makes before it falls back to sequential.
constexpr int optimise_max_posts = 8;

/// The most pairs of operations (channel A's times channel B's, in one section) the optimiser
/// weighs: its pairs and its schedule grow with that product, and a job beyond it (thousands of
/// head switches or tool changes between two barriers) is posted sequentially, with a warning,
/// in the memory and time of any post. 1000 operations a channel solve in about 0.2 s.
constexpr std::size_t optimise_max_section_pairs = 1'000'000;

/// `--sync optimise` for `o`'s job on machine `m`, posting with `attempt`; what reaches `diags`
/// is what the post that is kept said (and the optimiser's own errors and warnings).
/// `compare`: only the optimum is wanted (post --compare-optimum): nothing reaches `diags`, no
/// sequential post is made where none is found, and post_summary::optimum_unknown says why.
post_summary post_optimised(const post_options& o, const machine& m, diagnostic_sink& diags,
                            const post_attempt& attempt, bool compare = false);

}  // namespace twinpost
