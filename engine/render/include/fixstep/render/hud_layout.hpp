// Where the HUD's text goes: its lines wrapped to the frame's width, cut to its height, and the
// panel behind them placed in a corner (what Renderer::draw_hud draws, and the band a Session
// keeps free of the world).
#pragma once

#include <span>
#include <string>
#include <vector>

#include "fixstep/render/render.hpp"

namespace fixstep {

/// One line of HUD text as placed: its characters and its glyph cell's top-left corner, px
/// (x right, y down from the frame's top-left corner).
struct HudTextLine {
  std::string text;  ///< printable ASCII: the font's characters only (see Renderer::text)
  float x = 0.0f, y = 0.0f;
};

/// The HUD as drawn into a frame: the panel's rectangle [x0, x1) x [y0, y1), px, and its lines,
/// each inside it and inside the frame: a line's glyphs span [x, x + Renderer::text_width) by
/// [y, y + Renderer::text_height) at `scale`. No lines: nothing is drawn.
struct HudLayout {
  float x0 = 0.0f, y0 = 0.0f, x1 = 0.0f, y1 = 0.0f;  ///< px
  float scale = 1.0f;  ///< px per font pixel the lines are drawn at (the asked scale or less)
  std::vector<HudTextLine> lines;
  /// Whether lines were dropped at the bottom for want of height (the last shown ends "...").
  bool cut = false;
};

/// Lays the HUD's text `lines` out in a frame_width x frame_height frame (px, >= 1), in the
/// corner `corner`, at `scale` px per font pixel (Renderer::set_hud_text_scale's range).
///
/// Each line is turned into the font's characters (a UTF-8 sequence or other byte outside
/// ' '..'~' becomes one '?'), split at each '\n', then wrapped greedily at its spaces so that
/// no line is wider than the room the frame leaves (the frame's width less a 10 px margin and
/// the panel's 4-font-pixel padding on each side): a line breaks before the first word that
/// would run past it, the spaces at the break dropped and those between the words kept. A word
/// wider than the room by itself is broken between two characters, so every character is
/// drawn. A line that fits is kept as it is, so the HUD of a frame wide enough for it is
/// unchanged. The lines that do not fit the frame's height are dropped, and the last line kept
/// is shortened to end in "..." (HudLayout::cut).
///
/// In a frame too small for one glyph at `scale` with the margin and padding, the margin
/// shrinks first (to 0), then the padding, then the scale (in steps of 1/4, to 1/4 at least),
/// so the text stays inside the frame at any size a Renderer takes (min_frame_size and up).
/// Integer glyph widths times `scale`: the same layout on every platform.
/// Throws std::invalid_argument for a size below 1 px or a scale that is not finite and > 0.
[[nodiscard]] HudLayout layout_hud(std::span<const std::string> lines, float scale,
                                   HudCorner corner, int frame_width, int frame_height);

}  // namespace fixstep
