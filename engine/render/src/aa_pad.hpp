// The canvas's anti-aliasing margin, shared by render.cpp and render_shapes.cpp. Internal.
#pragma once

namespace fixstep::detail {

// How far quads reach beyond the edge of a line or disc, px. The fragment shader's coverage
// (1 - d) / fwidth(d) + 0.5 reaches 0 at half a fwidth beyond the edge: 0.5 px across an
// axis-aligned edge, at most sqrt(2) / 2 = 0.707 px across a diagonal one (fwidth is
// |d/dx| + |d/dy|). Fragments farther out blend with alpha 0, so 0.75 px draws the picture a
// whole pixel of padding drew (checked on 1000-body frames: all but one pixel within 1 level)
// with fewer fragments.
constexpr float aa_pad_px = 0.75f;

}  // namespace fixstep::detail
