// The CPU rasteriser of the overlay and HUD (engine/render/src/soft_shapes.hpp, OverlayPath::cpu)
// against llvmpipe drawing the same shapes (OverlayPath::gl), and against exact expectations:
// which pixel centres a shape covers, edges shared by two triangles blended once, a disc's
// coverage summing to its area, the clip box.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

#include "../../bench/many_bodies.hpp"  // bench_overlay's scene
#include "fixstep/app/session.hpp"
#include "fixstep/core/loop.hpp"
#include "fixstep/render/draw_list.hpp"
#include "overlay_shapes.hpp"
#include "scene_session.hpp"
#include "soft_shapes.hpp"

namespace fixstep {
namespace {

using detail::CanvasVertex;
using detail::PixelBox;
using detail::SoftRasteriser;

constexpr float no_hole = -1e30f;  // Renderer::no_hole

/// A width x height frame of one opaque colour.
std::vector<std::uint8_t> frame_of(int width, int height, Rgba8 c) {
  std::vector<std::uint8_t> f(std::size_t(width) * std::size_t(height) * 4);
  for (std::size_t k = 0; k < f.size(); k += 4) {
    f[k] = c.r, f[k + 1] = c.g, f[k + 2] = c.b, f[k + 3] = 255;
  }
  return f;
}

CanvasVertex solid(float x, float y, Rgba8 c) {
  return {x, y, 0, 0, c.r, c.g, c.b, c.a, no_hole};
}

/// Draws the triangles of `vertices` (3 each, in order) into `frame`, cut to `box`.
void draw(std::vector<std::uint8_t>& frame, int width, int height,
          const std::vector<CanvasVertex>& vertices, PixelBox box) {
  std::vector<std::uint32_t> indices(vertices.size());
  for (std::size_t k = 0; k < indices.size(); ++k) indices[k] = std::uint32_t(k);
  SoftRasteriser raster;
  raster.add(vertices, indices, box);
  raster.draw(frame, width, height);
}

const std::uint8_t* pixel(const std::vector<std::uint8_t>& frame, int width, int x, int y) {
  return &frame[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 4];
}

/// Expects the red channel 255 on the pixels of `white` and 0 on every other.
void expect_white_exactly(const std::vector<std::uint8_t>& frame, int width, int height,
                          PixelBox white) {
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const bool in = x >= white.x0 && x < white.x1 && y >= white.y0 && y < white.y1;
      EXPECT_EQ(pixel(frame, width, x, y)[0], in ? 255 : 0) << "pixel (" << x << ", " << y << ")";
    }
  }
}

TEST(SoftShapes, ARectangleCoversThePixelsWhoseCentresItHolds) {
  // [2.5, 7.5) x [1.5, 4.5): centres x + 0.5 in it for x = 2..6 (2.5 on the left edge is in, 7.5
  // on the right edge is out), y = 1..3.
  constexpr int w = 10, h = 6;
  auto frame = frame_of(w, h, {0, 0, 0, 255});
  const Rgba8 c{255, 255, 255, 255};
  draw(frame, w, h,
       {solid(2.5f, 1.5f, c), solid(7.5f, 1.5f, c), solid(7.5f, 4.5f, c), solid(2.5f, 1.5f, c),
        solid(7.5f, 4.5f, c), solid(2.5f, 4.5f, c)},
       {0, 0, w, h});
  expect_white_exactly(frame, w, h, {2, 1, 7, 4});
}

TEST(SoftShapes, TwoTrianglesSharingAnEdgeThroughPixelCentresBlendEachPixelOnce) {
  // A square cut along its diagonal, which passes exactly through the centres (i + 0.5, i +
  // 0.5), drawn translucent: a pixel blended twice would be brighter, one missed black.
  constexpr int w = 16, h = 16;
  auto frame = frame_of(w, h, {0, 0, 0, 255});
  const Rgba8 c{200, 200, 200, 128};
  // Not the renderer's quad order (a, b, c), (a, c, d): two separate triangles.
  draw(frame, w, h,
       {solid(0.5f, 0.5f, c), solid(12.5f, 0.5f, c), solid(12.5f, 12.5f, c), solid(12.5f, 12.5f, c),
        solid(0.5f, 12.5f, c), solid(0.5f, 0.5f, c)},
       {0, 0, w, h});
  const int once = pixel(frame, w, 5, 2)[0];  // well inside the first triangle
  EXPECT_NEAR(once, 200 * 128 / 255, 1);
  for (int y = 0; y < 12; ++y) {
    for (int x = 0; x < 12; ++x) {
      EXPECT_EQ(pixel(frame, w, x, y)[0], once) << "pixel (" << x << ", " << y << ")";
    }
  }
  EXPECT_EQ(pixel(frame, w, 12, 5)[0], 0);  // beyond the right edge
}

/// The renderer's disc of radius r px at (cx, cy), white over a black w x h frame: a quad
/// reaching 0.75 px beyond r with shape coordinates +-e. Returns the covered area, px^2 (the
/// red channel summed / 255).
double disc_area_drawn(int w, int h, float cx, float cy, float r) {
  auto frame = frame_of(w, h, {0, 0, 0, 255});
  const float pad = r + 0.75f, e = pad / r;
  auto at = [&](float x, float y, float u, float v) {
    return CanvasVertex{x, y, u, v, 255, 255, 255, 255, no_hole};
  };
  const std::vector<CanvasVertex> vertices = {
      at(cx - pad, cy - pad, -e, -e), at(cx + pad, cy - pad, e, -e), at(cx + pad, cy + pad, e, e),
      at(cx - pad, cy + pad, -e, e)};
  SoftRasteriser raster;
  raster.add(vertices, std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}, {0, 0, w, h});
  raster.draw(frame, w, h);
  double area = 0.0;
  for (std::size_t k = 0; k < frame.size(); k += 4) area += frame[k] / 255.0;
  return area;
}

TEST(SoftShapes, AnAntiAliasedDiscCoversItsArea) {
  // pi r^2 within 1 px^2 (the edge is a ramp about 1 px wide, its width from |ddx| + |ddy|, up
  // to sqrt(2) wider than the gradient on diagonals; seen 0.51 px^2 over at r = 5) or 0.2 %.
  for (const float r : {5.0f, 12.3f, 25.0f}) {
    const double exact = std::numbers::pi * r * r;
    EXPECT_NEAR(disc_area_drawn(64, 64, 31.7f, 32.2f, r), exact, std::max(1.0, 0.002 * exact))
        << "r = " << r;
  }
}

TEST(SoftShapes, ADiscCutByTheFramesTopAndBottomCoversWhatIsInside) {
  // A frame of odd height pairs its top row with row -1 in GL's 2x2 quads (they pair rows
  // counted from the bottom); nothing may be read or written there (ASan builds check it). A
  // disc whose centre is 0.4 px inside the top (bottom) edge covers its area less the
  // circular segment beyond the edge, r^2 acos(h / r) - h sqrt(r^2 - h^2) at depth h = 0.4 px,
  // within the disc test's tolerance, in frames of even and odd height.
  constexpr float r = 6.0f, inside = 0.4f;
  const double cut =
      double(r) * r * std::acos(inside / r) - inside * std::sqrt(r * r - inside * inside);
  const double exact = std::numbers::pi * r * r - cut;
  for (const int h : {16, 17}) {
    for (const float cy : {inside, float(h) - inside}) {
      EXPECT_NEAR(disc_area_drawn(40, h, 19.3f, cy, r), exact, std::max(1.0, 0.002 * exact))
          << "height " << h << ", centre y " << cy;
    }
  }
}

TEST(SoftShapes, NothingIsDrawnOutsideTheClipBox) {
  constexpr int w = 20, h = 20;
  auto frame = frame_of(w, h, {0, 0, 0, 255});
  const Rgba8 c{255, 255, 255, 255};
  draw(frame, w, h,
       {solid(-5.0f, -5.0f, c), solid(30.0f, -5.0f, c), solid(30.0f, 30.0f, c),
        solid(-5.0f, -5.0f, c), solid(30.0f, 30.0f, c), solid(-5.0f, 30.0f, c)},
       {4, 6, 9, 15});
  expect_white_exactly(frame, w, h, {4, 6, 9, 15});
}

/// Seeded random triangles and quads (solid, lines, discs, rings; rotated, reaching past every
/// edge) in a frame of 1 to 40 px a side, odd or even, cut to a random clip box, sometimes 400
/// at once (two threads).
struct RandomShapes {
  int w = 0, h = 0;
  std::vector<CanvasVertex> vertices;
  std::vector<std::uint32_t> indices;
  PixelBox box;
};

RandomShapes random_shapes(std::mt19937& rng, int round) {
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  RandomShapes r;
  r.w = 1 + int(rng() % 40), r.h = 1 + int(rng() % 40);
  const auto w = float(r.w), h = float(r.h);
  const int shapes = 1 + int(rng() % (round % 10 == 0 ? 400 : 6));
  for (int s = 0; s < shapes; ++s) {
    const float cx = (0.7f * unit(rng) + 0.5f) * w, cy = (0.7f * unit(rng) + 0.5f) * h;
    const float sx = 0.1f + std::abs(unit(rng)) * w, sy = 0.1f + std::abs(unit(rng)) * h;
    const int kind = int(rng() % 4);  // 0 a line's (u = 0), 1 a disc's, 2 a ring's, 3 solid
    const float fill = kind == 2 ? 0.7f : no_hole;
    const auto red = std::uint8_t(rng() % 256), alpha = std::uint8_t(rng() % 256);
    auto at = [&](float x, float y, float u, float v) {
      return CanvasVertex{x,
                          y,
                          kind == 0 || kind == 3 ? 0.0f : u,
                          kind == 3 ? 0.0f : v,
                          red,
                          std::uint8_t(255 - red),
                          100,
                          alpha,
                          fill};
    };
    const auto base = static_cast<std::uint32_t>(r.vertices.size());
    if (rng() % 3 == 0) {
      for (int k = 0; k < 3; ++k) {
        r.vertices.push_back(at(cx + unit(rng) * sx, cy + unit(rng) * sy, unit(rng), unit(rng)));
        r.indices.push_back(base + std::uint32_t(k));
      }
      continue;
    }
    const float c = unit(rng), sn = unit(rng), e = 1.2f;  // a quad, rotated and scaled
    for (const auto& [px, py] :
         {std::pair{-1.0f, -1.0f}, {1.0f, -1.0f}, {1.0f, 1.0f}, {-1.0f, 1.0f}}) {
      r.vertices.push_back(
          at(cx + c * px * sx - sn * py * sy, cy + sn * px * sx + c * py * sy, px * e, py * e));
    }
    for (const std::uint32_t k : {0u, 1u, 2u, 0u, 2u, 3u}) r.indices.push_back(base + k);
  }
  r.box = {0, 0, r.w, r.h};
  if (rng() % 2 != 0) {
    r.box.x0 = int(rng() % std::uint32_t(r.w));
    r.box.x1 = r.box.x0 + int(rng() % std::uint32_t(r.w - r.box.x0 + 1));
    r.box.y0 = int(rng() % std::uint32_t(r.h));
    r.box.y1 = r.box.y0 + int(rng() % std::uint32_t(r.h - r.box.y0 + 1));
  }
  return r;
}

TEST(SoftShapes, RandomShapesDrawOnlyInsideTheirFrameAndClipBox) {
  // No pixel outside the box changes and alpha stays 255. Under ASan (the asan preset) this
  // also checks that nothing is read or written outside the frame.
  std::mt19937 rng(20261126);
  for (int round = 0; round < 3000; ++round) {
    const RandomShapes r = random_shapes(rng, round);
    auto frame = frame_of(r.w, r.h, {0, 0, 0, 255});
    SoftRasteriser raster;
    raster.add(r.vertices, r.indices, r.box);
    raster.draw(frame, r.w, r.h);
    const PixelBox& box = r.box;
    for (int y = 0; y < r.h; ++y) {
      for (int x = 0; x < r.w; ++x) {
        const bool in = x >= box.x0 && x < box.x1 && y >= box.y0 && y < box.y1;
        const std::uint8_t* p = pixel(frame, r.w, x, y);
        ASSERT_TRUE(p[3] == 255 && (in || (p[0] == 0 && p[1] == 0 && p[2] == 0)))
            << "round " << round << ": pixel (" << x << ", " << y << ") of " << r.w << " x " << r.h
            << ", box [" << box.x0 << ", " << box.x1 << ") x [" << box.y0 << ", " << box.y1 << ")";
      }
    }
  }
}

/// Restores the rasteriser's choice of lanes when a test ends.
struct WideLanes {
  bool was = detail::soft_wide_lanes();
  ~WideLanes() { detail::set_soft_wide_lanes(was); }
};

TEST(SoftShapes, EightLanesDrawTheSamePixelsAsFour) {
  // The AVX2 path (two quads a vector) against the 4-lane one, byte for byte: the random shapes
  // above over a frame of varied colours, then bench_overlay's 1000 shapes over its scene.
  const WideLanes restore;
  detail::set_soft_wide_lanes(true);
  if (!detail::soft_wide_lanes()) GTEST_SKIP() << "this CPU has no AVX2: one path only";
  auto draw_both = [](const RandomShapes& r, std::vector<std::uint8_t> frame) {
    std::vector<std::uint8_t> out[2];
    for (const bool wide : {false, true}) {
      detail::set_soft_wide_lanes(wide);
      out[wide] = frame;
      SoftRasteriser raster;
      raster.add(r.vertices, r.indices, r.box);
      raster.draw(out[wide], r.w, r.h);
    }
    return std::pair{out[0], out[1]};
  };
  std::mt19937 rng(20261127);
  std::size_t changed = 0;  // bytes the shapes changed: the comparison is not of blank frames
  for (int round = 0; round < 3000; ++round) {
    const RandomShapes r = random_shapes(rng, round);
    std::vector<std::uint8_t> frame(std::size_t(r.w) * std::size_t(r.h) * 4);
    for (std::size_t k = 0; k < frame.size(); ++k) frame[k] = k % 4 == 3 ? 255 : rng() % 256;
    const auto [narrow, wide] = draw_both(r, frame);
    ASSERT_EQ(narrow, wide) << "round " << round << ", " << r.w << " x " << r.h;
    for (std::size_t k = 0; k < frame.size(); ++k) changed += narrow[k] != frame[k];
  }
  EXPECT_GT(changed, 100000u);
  Session session = testing::scene_session(bench::many_bodies(1000), 1280, 720);
  session.advance(0.1);
  DrawList list;
  testing::record_overlay(list, 0.1);
  std::vector<std::uint8_t> frames[2];
  for (const bool wide : {false, true}) {
    detail::set_soft_wide_lanes(wide);
    session.draw(list);
    frames[wide].assign(session.renderer().pixels().begin(), session.renderer().pixels().end());
  }
  EXPECT_TRUE(frames[0] == frames[1]) << "the 1000-shape overlay";
}

TEST(SoftShapes, TheOverlayMatchesLlvmpipeDrawingItToTwoLevels) {
  // bench_overlay's 1000 shapes (lines, polylines, discs, circles, hexagons, arrows, labels,
  // translucent) over its 1000-body scene and the HUD, drawn by GL (llvmpipe) and by the CPU.
  // The CPU rasteriser follows llvmpipe's rules (coverage at pixel centres, derivatives within
  // 2x2 quads, 8-bit blending), so they differ only by the rounding of a few levels on some
  // pixels: seen 1 level on 2.7 % of pixels and 2 on 55 of 921 600.
  Session session = testing::scene_session(bench::many_bodies(1000), 1280, 720);
  const VirtualClock clock(60.0);
  for (int f = 0; f < 5; ++f) session.advance(clock.frame_seconds());
  DrawList list;
  testing::record_overlay(list, 5 * clock.frame_seconds());
  session.set_overlay_path(OverlayPath::gl);
  session.draw(list);
  const std::vector<std::uint8_t> gl(session.renderer().pixels().begin(),
                                     session.renderer().pixels().end());
  session.set_overlay_path(OverlayPath::cpu);
  session.draw(list);
  const std::vector<std::uint8_t> cpu(session.renderer().pixels().begin(),
                                      session.renderer().pixels().end());
  ASSERT_EQ(cpu.size(), gl.size());
  int worst = 0;
  std::size_t differing = 0, drawn = 0;
  const std::vector<std::uint8_t> bare = [&] {
    session.draw();
    const auto p = session.renderer().pixels();
    return std::vector<std::uint8_t>(p.begin(), p.end());
  }();
  for (std::size_t k = 0; k < gl.size(); k += 4) {
    int most = 0;
    for (int ch = 0; ch < 3; ++ch) most = std::max(most, std::abs(int(gl[k + ch]) - cpu[k + ch]));
    worst = std::max(worst, most);
    differing += most > 0;
    drawn += gl[k] != bare[k] || gl[k + 1] != bare[k + 1] || gl[k + 2] != bare[k + 2];
  }
  const std::size_t pixels = gl.size() / 4;
  EXPECT_GT(drawn, pixels / 10) << "the overlay must cover a good part of the frame";
  EXPECT_LE(worst, 2);
  EXPECT_LE(differing, pixels / 20) << "pixels of the frame that differ at all";
}

}  // namespace
}  // namespace fixstep
