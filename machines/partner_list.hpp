#pragma once
// The partner list of a wait (Fanuc `M100 P12`): how a set of channels is written in the
// machine's style, and read back. The post writes lists with partner_list() and the checker
// reads them with decode_partner_list(), so the two cannot drift apart.
#include <string>
#include <string_view>
#include <vector>

#include "machines/machine.hpp"

namespace twinpost {

/// The partner list of a wait among `channels` (ascending, 1..64) in style `style`:
/// "12" / "123" for path numbers, the mask ("3", "7") for binary, "" for none; for others
/// the digits of `channels`, which the caller gives without the wait's own channel.
std::string partner_list(const std::vector<int>& channels, partner_style style);

/// Decodes a partner list value as written (`12` -> {1,2}; binary `3` -> {1,2}; others `23`
/// -> {2,3}, the markers between the digits of `!2!3L1` already taken out) into `out`;
/// false when `text` is not a list in that style: empty, a sign, a point, any other
/// character, or a binary mask beyond 64 bits. It reads only the form: channels the machine
/// does not have, a channel named twice or a list without the wait's own channel are the
/// checker's to report (check/sync_check), with the program's place.
bool decode_partner_list(std::string_view text, partner_style style, std::vector<int>& out);

}  // namespace twinpost
