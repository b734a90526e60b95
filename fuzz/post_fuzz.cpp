// libFuzzer target: mutated CL through the whole post — reader, router, wait allocation,
// channel writers, framing, the self-check and the commit of the output set — in a scratch
// folder, on every built-in machine and layout (the first byte picks them). Properties:
// - post_job returns or throws config_error (exit 0, 1 or 2 in the tool), nothing else;
// - a failed post leaves the output folder as it was (here: absent or empty);
// - every error has a file, and a line unless it is about the whole job;
// - a post that succeeds wrote the files it names, and `check` finds them sound;
// - no word of a posted program is unreadable: no inf or nan, no number of more than ten
//   digits outside comments (the machine's word formats are tighter still); a job with an
//   INSERT record (raw NC text, written verbatim) is not held to this one;
// - the same input posted again gives the same bytes.
#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "check/sync_check.hpp"
#include "fuzz/fuzz_support.hpp"
#include "machines/layout_rules.hpp"
#include "post/post_job.hpp"
#include "support/ascii.hpp"
#include "support/errors.hpp"

namespace fs = std::filesystem;
using namespace twinpost;

namespace {

// True when the job holds the word INSERT in any case (a record of raw NC text).
bool contains_insert(std::string_view cl) {
  for (std::size_t i = 0; i < cl.size(); ++i)
    if (ascii::starts_with_keyword(cl.substr(i), "INSERT")) return true;
  return false;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::vector<machine>& all = fuzz::builtin_machine_defs();
  const machine& m = all[data[0] % all.size()];
  static constexpr layout_kind layouts[] = {layout_kind::split, layout_kind::merged_appended,
                                            layout_kind::merged_sections};
  layout_kind layout = layouts[(data[0] / all.size()) % 3];
  // A layout the machine cannot take is refused before posting (machines/layout_rules).
  if (!layout_problem(m, layout).empty()) layout = layout_kind::merged_sections;
  const std::string dir = fuzz::scratch_dir();
  const std::string job = dir + "/job.cls";
  fuzz::write_all(job, std::string_view(reinterpret_cast<const char*>(data) + 1, size - 1));
  const std::string_view cl(reinterpret_cast<const char*>(data) + 1, size - 1);
  const bool has_insert = contains_insert(cl);
  const fuzz::post_outcome first = fuzz::post_checked(job, dir + "/out", m, layout, has_insert);
  if (!first.ok) return 0;
  const fuzz::post_outcome second = fuzz::post_checked(job, dir + "/again", m, layout, has_insert);
  fuzz::require(second.ok && second.contents == first.contents,
                "the same job posted twice gave different bytes");
  return 0;
}
