// The CPU rasteriser of the overlay (engine/render/src/soft_shapes.hpp) allocates nothing for a
// frame once warm. In test_contact_events, which counts what operator new is asked for
// (count_new.cpp) and never renders through llvmpipe: the rasteriser needs no GL context.
#include <gtest/gtest.h>

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "soft_shapes.hpp"

extern std::atomic<bool> counting;              // count_new.cpp
extern std::atomic<std::size_t> counted_bytes;  // bytes asked for while counting

namespace fixstep {
namespace {

using detail::CanvasVertex;
using detail::SoftRasteriser;

TEST(SoftShapesMemory, AWarmFrameAllocatesNothing) {
  // 600 anti-aliased discs over a 320 x 181 frame (odd: its top row pairs with row -1): enough
  // pieces for the second thread, which the first frame starts.
  constexpr int w = 320, h = 181;
  std::vector<std::uint8_t> frame(std::size_t(w) * h * 4, 255);
  std::vector<CanvasVertex> vertices;
  std::vector<std::uint32_t> indices;
  for (int i = 0; i < 600; ++i) {
    const float cx = float((i * 37) % w), cy = float((i * 61) % h), r = 3.0f + float(i % 5);
    const float pad = r + 0.75f, e = pad / r;
    const auto base = static_cast<std::uint32_t>(vertices.size());
    for (const auto& [sx, sy] :
         {std::pair{-1.0f, -1.0f}, {1.0f, -1.0f}, {1.0f, 1.0f}, {-1.0f, 1.0f}}) {
      vertices.push_back(
          CanvasVertex{cx + sx * pad, cy + sy * pad, sx * e, sy * e, 200, 100, 50, 180, -1e30f});
    }
    for (const std::uint32_t k : {0u, 1u, 2u, 0u, 2u, 3u}) indices.push_back(base + k);
  }
  SoftRasteriser raster;
  auto frame_once = [&] {
    raster.add(vertices, indices, {0, 0, w, h});
    raster.draw(frame, w, h);
  };
  frame_once();
  counted_bytes = 0;
  counting = true;
  frame_once();
  frame_once();
  counting = false;
  EXPECT_EQ(counted_bytes, 0u);
}

}  // namespace
}  // namespace fixstep
