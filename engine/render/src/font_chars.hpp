// Internal to fixstep::render: text in the HUD font's characters.
#pragma once

#include <string>

namespace fixstep::detail {

/// `s` in the characters the HUD font (stb_easy_font) has glyphs for, into `out` (its storage
/// reused): the font indexes its glyph table with (char - 32) and has ' '..'~' only, so any other
/// byte would read outside the table. Each UTF-8 sequence (or other byte) outside that range
/// becomes one '?' (continuation bytes dropped); '\n' is kept (a new line).
inline void font_chars_into(const std::string& s, std::string& out) {
  out.clear();
  out.reserve(s.size());
  for (const char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    if ((c >= 32 && c <= 126) || c == '\n') {
      out.push_back(ch);
    } else if ((c & 0xC0) != 0x80) {
      out.push_back('?');
    }
  }
}

}  // namespace fixstep::detail
