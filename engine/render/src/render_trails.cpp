// Renderer::draw_trails: each body's trail (Trails, sampled per tick) as one fading polyline.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#include "fixstep/render/render.hpp"
#include "scene_palette.hpp"

namespace fixstep {

namespace {

// Trail samples may be left up to this far from the drawn polyline, px (see draw()).
constexpr float trail_tolerance_px = 0.2f;

// Four floats in one SSE register (GCC and clang vector extensions): each operation below acts on
// the four lanes exactly as the scalar one would on each.
using float4 = float __attribute__((vector_size(16)));

// Is any of the four points (xs[0..3], ys[0..3]) farther than sqrt(tol2) px from the segment from
// (ax, ay) to (ax + ux, ay + uy)? inv_len2 is 1 / (ux² + uy²), or 0 for a zero-length segment.
bool any_beyond(const float* xs, const float* ys, float ax, float ay, float ux, float uy,
                float inv_len2, float tol2) {
  float4 x, y;
  std::memcpy(&x, xs, sizeof x);
  std::memcpy(&y, ys, sizeof y);
  const float4 wx = x - ax, wy = y - ay;
  float4 t = (wx * ux + wy * uy) * inv_len2;
  t = t < 0.0f ? 0.0f : t;  // std::clamp(t, 0, 1), lane by lane
  t = 1.0f < t ? 1.0f : t;
  const float4 dx = wx - t * ux, dy = wy - t * uy;
  const auto beyond = dx * dx + dy * dy > tol2;  // lanes of all ones where true
  return (beyond[0] | beyond[1] | beyond[2] | beyond[3]) != 0;
}

// Chooses which of the n points (xs[i], ys[i]) a polyline keeps, greedily: from each kept point,
// the next one kept is the farthest along that leaves every point in between within `tolerance`
// px of the segment joining the two, and at most max_run points on. The first and last points
// are always kept. Writes the kept indices, in order, to `kept` (room for n) and returns their
// number. O(n * max_run) distance computations, on coordinate arrays (the trails' own layout),
// four at a time.
int simplify_polyline(const float* xs, const float* ys, int n, float tolerance, int* kept) {
  if (n < 3) {
    for (int i = 0; i < n; ++i) kept[i] = i;
    return n;
  }
  const float tol2 = tolerance * tolerance;
  constexpr int max_run = 12;
  // Is every point strictly between `from` and `to` within tolerance of the segment joining
  // them?
  auto fits = [&](int from, int to) {
    const float ax = xs[from], ay = ys[from];
    const float ux = xs[to] - ax, uy = ys[to] - ay, len2 = ux * ux + uy * uy;
    const float inv_len2 = len2 > 0.0f ? 1.0f / len2 : 0.0f;
    int i = from + 1;
    for (; i + 4 <= to; i += 4) {
      if (any_beyond(xs + i, ys + i, ax, ay, ux, uy, inv_len2, tol2)) return false;
    }
    for (; i < to; ++i) {
      const float wx = xs[i] - ax, wy = ys[i] - ay;
      const float t = std::clamp((wx * ux + wy * uy) * inv_len2, 0.0f, 1.0f);
      const float dx = wx - t * ux, dy = wy - t * uy;
      if (dx * dx + dy * dy > tol2) return false;
    }
    return true;
  };
  int count = 0, anchor = 0;
  kept[count++] = 0;
  while (anchor + 1 < n) {
    int end = anchor + 1;
    while (end + 1 < n && end - anchor < max_run && fits(anchor, end + 1)) ++end;
    kept[count++] = end;
    anchor = end;
  }
  return count;
}

}  // namespace

void Renderer::draw_trails(const RenderFrame& s, double scale) {
  // Trails: one polyline per body through its samples (evenly spaced in time: Trails) and its
  // drawn position, fading from transparent (oldest) to 60 % opaque (now): point k of count
  // (0 = oldest) has alpha 150 (k + 0.5) / count, so a trail still shorter than its trail_time
  // (a body just created) fades along its whole length too.
  // Samples are then dropped where the polyline can skip them without leaving any of them more
  // than trail_tolerance_px away (simplify_polyline): a trail of 44 sub-pixel segments becomes a
  // few segments of a few pixels, and a projectile's gentle parabola a few long ones. Samples
  // are kept in m and drawn through this frame's camera, so a moving camera (Session::follow)
  // shows where the body went, not where it was on the screen.
  for (std::size_t j = 0; j < s.x.size(); ++j) {
    if (!scene_palette::body_visible(s, j)) continue;
    std::array<float, Trails::max_points> xs, ys, ages;  // oldest first (ages unused here)
    const int count = trails_.points(s, j, xs, ys, ages);
    if (count < 2) continue;
    for (int k = 0; k < count; ++k) {
      const auto p = to_pixel(xs[k], ys[k]);
      xs[k] = static_cast<float>(p[0]);
      ys[k] = static_cast<float>(p[1]);
    }
    std::array<int, Trails::max_points> kept;
    const int simplified =
        simplify_polyline(xs.data(), ys.data(), count, trail_tolerance_px, kept.data());
    const Rgba8 c = scene_palette::body_color(s, j);
    polyline_scratch_.clear();
    for (int i = 0; i < simplified; ++i) {
      const int k = kept[i];
      Rgba8 ck = c;
      ck.a = static_cast<std::uint8_t>((300 * k + 150) / (2 * count));
      polyline_scratch_.push_back({xs[k], ys[k], ck});
    }
    // Its newest end is the body's centre, under the body's disc.
    shorten(polyline_scratch_, 0.0f,
            hidden_under_disc(
                scene_palette::body_radius_px(s, j, scale) + scene_palette::outline_px, 2.0f));
    polyline(polyline_scratch_, 2.0f);
  }
}

}  // namespace fixstep
