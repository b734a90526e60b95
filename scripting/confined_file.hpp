#pragma once
// Reading a file a machine's script names (the script itself, post.read_file): only a regular
// file, in the machine file's folder, of bounded size (docs/scripting.md, "What a script
// cannot do").
#include <cstddef>
#include <string>

namespace twinpost::scripting {

/// Why a read was refused.
enum class read_refusal { none, missing, symlink, not_regular, too_large, other };

/// Reads `path` into `out`. The file is opened with O_NOFOLLOW (a symbolic link is refused, not
/// followed), O_NONBLOCK (a FIFO cannot block the post) and O_CLOEXEC, and must be a regular
/// file of at most `max_bytes` bytes (by fstat and as read). On a refusal `out` is empty and
/// `why` holds the system's reason for `other`.
read_refusal read_confined(const std::string& path, std::size_t max_bytes, std::string& out,
                           std::string& why);

}  // namespace twinpost::scripting
