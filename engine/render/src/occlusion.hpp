// What the scene view draws later hides (Renderer::hidden_under_disc, hidden_under_square and
// shorten, whose code this is): free functions, for the steps of the scene view in
// render_frame.cpp, which are not members of Renderer. Internal to fixstep::render.
#pragma once

#include <span>

#include "fixstep/render/render.hpp"

namespace fixstep::detail {

/// px by which a line of `width` px ending at the centre of an outlined disc of outer radius
/// `outer` px (drawn over it later) can stop short without changing the picture.
[[nodiscard]] float hidden_under_disc(float outer, float width);
/// px by which a line of `width` px leaving the centre of an opaque solid square of half-side
/// `half` px (drawn over it later) in unit direction (ux, uy) can start late, likewise.
[[nodiscard]] float hidden_under_square(float half, float width, float ux, float uy);
/// Moves the first of `points` along the first segment by `cut_start` px and the last back
/// along the last segment by `cut_end` px (Renderer::shorten).
void shorten(std::span<Renderer::PolylinePoint> points, float cut_start, float cut_end);

}  // namespace fixstep::detail
