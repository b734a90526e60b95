#include "support/json.hpp"

#include <cstdint>

namespace twinpost {

namespace {

/// The code point of the valid UTF-8 sequence at `s[i]` and its length, or length 0 when
/// the bytes there are not one (a stray continuation byte, a cut sequence, an overlong
/// form, a surrogate, a value past U+10FFFF).
struct utf8_char {
  char32_t code = 0;
  std::size_t length = 0;
};

utf8_char decode_utf8(std::string_view s, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char c = byte(i);
  const std::size_t len = (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xE ? 3 : (c >> 3) == 0x1E ? 4 : 0;
  if (len == 0 || i + len > s.size()) return {};
  char32_t code = c & (0x7F >> len);
  for (std::size_t k = 1; k < len; ++k) {
    if ((byte(i + k) & 0xC0) != 0x80) return {};
    code = (code << 6) | (byte(i + k) & 0x3F);
  }
  constexpr char32_t smallest[] = {0, 0, 0x80, 0x800, 0x10000};
  if (code < smallest[len] || (code >= 0xD800 && code <= 0xDFFF) || code > 0x10FFFF) return {};
  return {code, len};
}

void append_u_escape(std::string& out, std::uint32_t unit) {
  constexpr char hex[] = "0123456789abcdef";
  out += "\\u";
  for (int shift = 12; shift >= 0; shift -= 4) out += hex[(unit >> shift) & 0xF];
}

}  // namespace

void append_json_string(std::string& out, std::string_view s) {
  out += '"';
  for (std::size_t i = 0; i < s.size();) {
    const auto c = static_cast<unsigned char>(s[i]);
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      case '\b': out += "\\b"; break;
      case '\f': out += "\\f"; break;
      default:
        if (c >= 0x20 && c < 0x7F) {
          out += static_cast<char>(c);
        } else if (const utf8_char u = c >= 0x80 ? decode_utf8(s, i) : utf8_char{}; u.length) {
          if (u.code < 0x10000) {
            append_u_escape(out, u.code);
          } else {  // JSON spells a character past the BMP as a UTF-16 surrogate pair
            append_u_escape(out, 0xD800 + ((u.code - 0x10000) >> 10));
            append_u_escape(out, 0xDC00 + ((u.code - 0x10000) & 0x3FF));
          }
          i += u.length;
          continue;
        } else {
          append_u_escape(out, c);  // a control, DEL, or a byte read as ISO-8859-1
        }
    }
    ++i;
  }
  out += '"';
}

std::string json_quote(std::string_view s) {
  std::string out;
  out.reserve(s.size() + 2);
  append_json_string(out, s);
  return out;
}

}  // namespace twinpost
