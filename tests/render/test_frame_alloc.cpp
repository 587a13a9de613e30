// fill_render_frame reuses its frame's storage: a warm fill of a world with shapes and discs
// allocates nothing. In test_contact_events, which counts what operator new is asked for
// (count_new.cpp) and renders nothing.
#include <gtest/gtest.h>

#include <atomic>
#include <cstddef>

#include "fixstep/core/components.hpp"
#include "fixstep/core/shape.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "fixstep/render/frame_data.hpp"

extern std::atomic<bool> counting;              // count_new.cpp
extern std::atomic<std::size_t> counted_bytes;  // bytes asked for while counting

namespace fixstep {
namespace {

TEST(FrameDataMemory, AWarmFillOfAWorldWithShapesAllocatesNothing) {
  World sim(WorldDef::empty(Precision::f64, WorldSettings{}));
  for (int i = 0; i < 20; ++i) {
    BodyDef d;
    d.body.position = {2.0 * i, 0.0};
    d.body.angular_velocity = 1.0;
    if (i % 2 == 0) {
      d.shapes = {ShapeDef{.kind = ShapeKind::box, .radius = 0.0, .half_extents = {0.5, 0.25}},
                  ShapeDef{.kind = ShapeKind::circle, .radius = 0.3, .offset = {0.5, 0.0}}};
    } else {
      d.collider = Collider{.radius = 0.5};
    }
    sim.create_body(d);
  }
  RenderFrame s;
  fill_render_frame(sim, 0.5, s);
  ASSERT_EQ(s.shapes.size(), 20u);
  sim.step();
  counted_bytes = 0;
  counting = true;
  fill_render_frame(sim, 0.25, s);
  fill_render_frame(sim, 0.75, s);
  counting = false;
  EXPECT_EQ(counted_bytes, 0u);
  EXPECT_EQ(s.shapes.size(), 20u);
}

}  // namespace
}  // namespace fixstep
