// fill_render_frame reuses its frame's storage: a warm fill of a world with shapes and discs
// allocates nothing. In test_contact_events, which counts what operator new is asked for
// (count_new.cpp) and renders nothing.
#include <gtest/gtest.h>

#include <atomic>
#include <cstddef>
#include <optional>

#include "fixstep/core/components.hpp"
#include "fixstep/core/joint.hpp"
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

// Joints: their marks are refreshed every frame from World::joint_state; their definitions (a
// name longer than a short string among them) are read once per handle.
TEST(FrameDataMemory, AWarmFillOfAWorldWithJointsAllocatesNothing) {
  World sim(WorldDef::empty(Precision::f64, WorldSettings{}));
  Entity previous{};
  for (int i = 0; i < 10; ++i) {
    BodyDef d;
    d.body.position = {1.0 * i, 0.0};
    d.gravity = Gravity{{0.0, -9.81}};
    d.shapes = {ShapeDef{.kind = ShapeKind::box, .radius = 0.0, .half_extents = {0.4, 0.1}}};
    const Entity e = sim.create_body(d);
    sim.create_joint(JointDef{.type = i % 2 ? JointType::revolute : JointType::distance,
                              .body_a = previous,
                              .body_b = e,
                              .anchor = {i - 0.5, 0.0},
                              .anchor_b = i % 2 ? std::nullopt : std::optional(Vec2{i - 0.4, 0.0}),
                              .lower = i % 2 ? std::optional(-0.5) : std::nullopt,
                              .upper = 1.0,
                              .name = "a joint named at more length than a short string holds"});
    previous = e;
  }
  sim.set_keep_previous(true);
  RenderFrame s;
  fill_render_frame(sim, 0.5, s);
  ASSERT_EQ(s.joints.size(), 10u);
  sim.step();
  counted_bytes = 0;
  counting = true;
  fill_render_frame(sim, 0.25, s);
  fill_render_frame(sim, 0.75, s);
  counting = false;
  EXPECT_EQ(counted_bytes, 0u);
  EXPECT_EQ(s.joints.size(), 10u);
}

}  // namespace
}  // namespace fixstep
