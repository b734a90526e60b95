#pragma once
// CAM dialects of CL text and the conventions that differ between them.
#include <array>
#include <optional>
#include <string_view>

namespace twinpost {

enum class dialect : unsigned char { generic, creo, nx, catia, solidworks, makino };

/// Guesses the dialect from the first bytes of a file: Creo `$$* Pro/CLfile`, NX
/// `TOOL PATH/`, CATIA `$$*CATIA0`, Makino `APTCL-SPEC,MAKINO`, SolidWorks CAM `UNIT/MM`,
/// `CSI_SET_` or `OPFEATSTART`; generic ISO 4343 APT otherwise.
dialect detect_dialect(std::string_view head);

struct dialect_name_entry {
  dialect value;
  std::string_view name;  ///< as --dialect spells it
};

/// The one table of dialect names, in the order messages and help texts list them.
inline constexpr std::array<dialect_name_entry, 6> dialect_names{{
    {dialect::creo, "creo"},
    {dialect::nx, "nx"},
    {dialect::catia, "catia"},
    {dialect::solidworks, "solidworks"},
    {dialect::makino, "makino"},
    {dialect::generic, "generic"},
}};

/// The dialect's name as used by --dialect ("creo", "nx", ...).
std::string_view dialect_name(dialect d);

/// The dialect named `name`, if any.
std::optional<dialect> dialect_from_name(std::string_view name);

/// True when the dialect's CIRCLE moves counter-clockwise about its (i,j,k): Creo,
/// SolidWorks CAM, CATIA and generic APT; NX and Makino-style files move clockwise.
bool circle_is_ccw(dialect d);

/// What a dialect's CYCLE words mean, where they differ between CAM systems (docs/records.md,
/// "Cycle words", with the source of each). A word whose meaning is not known for the dialect
/// stops the post at the CYCLE record.
struct cycle_word_meaning {
  /// FEDTO,d: a positive depth below the hole's top (the GOTO point), not an absolute Z.
  bool fedto_is_depth = false;
  /// RTRCTO,h: the retract (initial) plane h above the hole's top, where the tool waits
  /// before and returns after each hole; false: RTRCTO is not known in this dialect.
  bool rtrcto_above_top = false;
  /// DWELL,t: seconds at the bottom of the hole (0: none).
  bool dwell_seconds = false;
  /// DEEP2 with 1STPECK,a,SUBPECK,b: chip-breaking pecks, a first, then b.
  bool first_and_later_pecks = false;
  /// FEDTO,d: a signed distance from the hole's top (the GOTO point) along the tool axis,
  /// negative into the part (NX: the feed-to position is the point + d × the tool axis).
  bool fedto_along_axis = false;
  /// FEDTO,d is a Z of the part frame (neither a depth nor a distance along the tool).
  bool fedto_absolute() const { return !fedto_is_depth && !fedto_along_axis; }
};

/// The meaning of the cycle words in dialect `d`.
cycle_word_meaning cycle_meaning(dialect d);

}  // namespace twinpost
