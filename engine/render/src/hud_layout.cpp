// The HUD's text laid out to fit its frame (fixstep/render/hud_layout.hpp).
#include "fixstep/render/hud_layout.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string_view>

#include "font_chars.hpp"

namespace fixstep {

namespace {

// Sizes of the panel: the margin in px at any scale, the rest in font pixels times the scale.
constexpr float layout_margin = 10.0f;    // px from the frame's corner
constexpr float layout_pad = 4.0f;        // font px round the text (the panel's top and sides)
constexpr float layout_line_h = 11.0f;    // font px from one line's top to the next
constexpr float hud_widest_glyph = 9.0f;  // font px: '@', the widest advance of the font
constexpr std::string_view hud_ellipsis = "...";

/// The font's advance of each printable character, font px (Renderer::text_width of the
/// character alone: stb_easy_font's width of a line is the sum of its characters' advances).
const std::array<int, 128>& hud_advances() {
  static const std::array<int, 128> table = [] {
    std::array<int, 128> a{};
    for (int c = 32; c < 127; ++c) {
      a[static_cast<std::size_t>(c)] =
          static_cast<int>(Renderer::text_width(std::string(1, static_cast<char>(c)), 1.0f));
    }
    return a;
  }();
  return table;
}

/// Width of printable ASCII `s`, font px.
int hud_font_width(std::string_view s) {
  int w = 0;
  for (const char c : s) w += hud_advances()[static_cast<unsigned char>(c) & 127u];
  return w;
}

/// `s` in the font's characters (as Renderer::text draws it): each byte or UTF-8 sequence
/// outside ' '..'~' becomes one '?', '\n' kept.
std::string hud_font_chars(const std::string& s) {
  std::string out;
  detail::font_chars_into(s, out);
  return out;
}

/// The longest prefix of `word` (at least one character) at most `room` font px wide.
std::size_t hud_fitting_prefix(std::string_view word, int room) {
  std::size_t k = 0;
  for (int w = 0; k < word.size(); ++k) {
    w += hud_advances()[static_cast<unsigned char>(word[k]) & 127u];
    if (w > room) break;
  }
  return std::max<std::size_t>(k, 1);
}

/// A piece of a line and the run of spaces before it ("" before the first).
struct HudPiece {
  std::string_view gap, text;
};

/// The pieces of `s` between its runs of at least `min_gap` spaces, in order; the spaces at
/// either end dropped (none: no piece).
std::vector<HudPiece> hud_pieces(std::string_view s, std::size_t min_gap) {
  std::vector<HudPiece> out;
  const std::size_t first = s.find_first_not_of(' ');
  if (first == std::string_view::npos) return out;
  s = s.substr(first, s.find_last_not_of(' ') + 1 - first);
  std::size_t piece = 0;
  std::string_view gap_before;
  for (std::size_t i = 0; i < s.size();) {
    const std::size_t gap = s.find(' ', i);
    if (gap == std::string_view::npos) break;
    const std::size_t next = s.find_first_not_of(' ', gap);  // s ends in a non-space
    if (next - gap >= min_gap) {
      out.push_back({gap_before, s.substr(piece, gap - piece)});
      gap_before = s.substr(gap, next - gap);
      piece = next;
    }
    i = next;
  }
  out.push_back({gap_before, s.substr(piece)});
  return out;
}

/// Wraps one line (no '\n') to `room` font px, appending its lines to `out` until it holds more
/// than `limit` (the rest could not be shown): fields (the pieces between runs of two or more
/// spaces, as the HUD's lines separate their items) are packed first; a field wider than a line
/// by itself goes word by word, and a word wider than a line by itself is broken between
/// characters. Linear in the line's length (a guard's message may name a 2 MB body name).
void hud_wrap_line(std::string_view text, int room, std::size_t limit,
                   std::vector<std::string>& out) {
  if (out.size() > limit) return;
  if (hud_font_width(text) <= room) {
    out.emplace_back(text);
    return;
  }
  std::string line;
  int line_w = 0;  // font px of `line`
  // Appends `gap` and `piece` to the line when the result fits; else false.
  auto extend = [&](std::string_view gap, std::string_view piece) {
    const int w =
        line.empty() ? hud_font_width(piece) : line_w + hud_font_width(gap) + hud_font_width(piece);
    if (w > room) return false;
    if (!line.empty()) line += gap;
    line += piece;
    line_w = w;
    return true;
  };
  auto flush = [&] {
    if (!line.empty()) out.push_back(std::move(line));
    line.clear();
    line_w = 0;
  };
  for (const auto& [gap, field] : hud_pieces(text, 2)) {
    if (out.size() > limit) return;
    if (extend(gap, field)) continue;
    if (!line.empty() && hud_font_width(field) <= room) {
      flush();
      extend({}, field);
      continue;
    }
    bool first = true;
    for (auto [word_gap, word] : hud_pieces(field, 1)) {
      if (out.size() > limit) return;
      const std::string_view before = first ? gap : word_gap;
      first = false;
      if (extend(before, word)) continue;
      flush();
      for (std::size_t k = hud_fitting_prefix(word, room); k < word.size() && out.size() <= limit;
           k = hud_fitting_prefix(word, room)) {
        out.emplace_back(word.substr(0, k));
        word.remove_prefix(k);
      }
      if (!extend({}, word)) {  // what is left fits, but in a frame narrower than one glyph
        line.assign(word);
        line_w = hud_font_width(word);
      }
    }
  }
  flush();
}

/// `line` shortened to end in "..." within `room` font px.
std::string hud_with_ellipsis(std::string line, int room) {
  const int dots = hud_font_width(hud_ellipsis);
  while (!line.empty() && (hud_font_width(line) + dots > room || line.back() == ' '))
    line.pop_back();
  return line + std::string(hud_ellipsis);
}

/// The panel's margin (px), padding (px) and scale for a frame `w` x `h` px: as asked, or less
/// when one glyph and one line would not fit (hud_layout.hpp).
struct HudMetrics {
  float margin, pad, scale;
};
HudMetrics fit_hud_metrics(float scale, float w, float h) {
  HudMetrics m{layout_margin, layout_pad * scale, scale};
  // One glyph across and one line down (the panel of one line is pad + 12·scale tall): the
  // least room left, px.
  auto room = [&] {
    return std::min(w - 2 * m.margin - 2 * m.pad - hud_widest_glyph * m.scale,
                    h - 2 * m.margin - m.pad - 12.0f * m.scale);
  };
  if (room() >= 0) return m;
  m.margin = std::max(0.0f, std::floor(std::min(0.5f * (w - 2 * m.pad - hud_widest_glyph * scale),
                                                0.5f * (h - m.pad - 12.0f * scale))));
  if (room() >= 0) return m;
  m.margin = 0;
  m.pad = std::clamp(std::floor(std::min(0.5f * (w - hud_widest_glyph * scale), h - 12.0f * scale)),
                     0.0f, m.pad);
  if (room() >= 0) return m;
  m.pad = 0;
  while (m.scale > 0.25f && room() < 0) m.scale -= 0.25f;
  return m;
}

}  // namespace

HudLayout layout_hud(std::span<const std::string> lines, float scale, HudCorner corner,
                     int frame_width, int frame_height) {
  if (frame_width < 1 || frame_height < 1) {
    throw std::invalid_argument(
        fmt::format("layout_hud: frame {}x{} is below 1x1", frame_width, frame_height));
  }
  if (!(std::isfinite(scale) && scale > 0.0f)) {
    throw std::invalid_argument(fmt::format("layout_hud: text scale {} is not > 0", scale));
  }
  HudLayout out;
  if (lines.empty()) return out;
  const float w = float(frame_width), h = float(frame_height);
  const HudMetrics m = fit_hud_metrics(scale, w, h);
  const float s = m.scale;
  out.scale = s;
  // Room for the text, font px: across, and how many lines down.
  const int room = std::max(0, static_cast<int>(std::floor((w - 2 * m.margin - 2 * m.pad) / s)));
  const auto rows = static_cast<std::size_t>(
      std::max(1.0f, std::floor((h - 2 * m.margin - m.pad - s) / (layout_line_h * s))));
  std::vector<std::string> wrapped;
  for (const std::string& line : lines) {
    const std::string chars = hud_font_chars(line);
    std::size_t start = 0;
    for (std::size_t nl = chars.find('\n'); nl != std::string::npos; nl = chars.find('\n', start)) {
      hud_wrap_line(std::string_view(chars).substr(start, nl - start), room, rows, wrapped);
      start = nl + 1;
    }
    hud_wrap_line(std::string_view(chars).substr(start), room, rows, wrapped);
  }
  if (wrapped.size() > rows) {
    wrapped.resize(rows);
    wrapped.back() = hud_with_ellipsis(std::move(wrapped.back()), room);
    out.cut = true;
  }
  int widest = 0;
  for (const std::string& l : wrapped) widest = std::max(widest, hud_font_width(l));
  const float panel_w = float(widest) * s + 2 * m.pad;
  const float panel_h = m.pad + (layout_line_h * float(wrapped.size()) + 1.0f) * s;
  const bool right = corner == HudCorner::top_right || corner == HudCorner::bottom_right;
  const bool bottom = corner == HudCorner::bottom_left || corner == HudCorner::bottom_right;
  out.x0 = right ? std::max(m.margin, w - m.margin - panel_w) : m.margin;
  out.y0 = bottom ? std::max(m.margin, h - m.margin - panel_h) : m.margin;
  out.x1 = out.x0 + panel_w;
  out.y1 = out.y0 + panel_h;
  out.lines.reserve(wrapped.size());
  float y = out.y0 + m.pad;
  for (std::string& l : wrapped) {
    out.lines.push_back({std::move(l), out.x0 + m.pad, y});
    y += layout_line_h * s;
  }
  return out;
}

}  // namespace fixstep
