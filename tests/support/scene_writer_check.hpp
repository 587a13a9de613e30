// Field-by-field, bit-for-bit comparison of two WorldDefs, for the scene writer's tests
// (test_scene_writer.cpp): the definition hash leaves names and appearances out, this does not.
#pragma once

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <optional>
#include <string>

#include "fixstep/core/components.hpp"
#include "fixstep/core/joint.hpp"
#include "fixstep/core/segment.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"

namespace fixstep::test {

/// Equal bits: 0.0 and -0.0 differ, as they do in the definition hash.
inline void expect_bits(double a, double b, const std::string& what) {
  EXPECT_EQ(std::bit_cast<std::uint64_t>(a), std::bit_cast<std::uint64_t>(b))
      << what << ": " << a << " vs " << b;
}
inline void expect_bits(Vec2 a, Vec2 b, const std::string& what) {
  expect_bits(a.x, b.x, what + ".x");
  expect_bits(a.y, b.y, what + ".y");
}
inline void expect_bits(const std::optional<double>& a, const std::optional<double>& b,
                        const std::string& what) {
  ASSERT_EQ(a.has_value(), b.has_value()) << what;
  if (a) expect_bits(*a, *b, what);
}

/// f(a, b) when both are set; that both or neither are.
template <class T, class F>
void expect_optional(const std::optional<T>& a, const std::optional<T>& b, const std::string& what,
                     F&& f) {
  ASSERT_EQ(a.has_value(), b.has_value()) << what;
  if (a) f(*a, *b);
}

inline void expect_same_body(const BodyDef& a, const BodyDef& b, const std::string& w) {
  EXPECT_EQ(a.name, b.name) << w;
  EXPECT_EQ(a.type, b.type) << w;
  expect_bits(a.body.mass, b.body.mass, w + ".mass");
  expect_bits(a.body.position, b.body.position, w + ".position");
  expect_bits(a.body.velocity, b.body.velocity, w + ".velocity");
  expect_optional(a.spring, b.spring, w + ".spring", [&](const auto& x, const auto& y) {
    expect_bits(x.anchor, y.anchor, w + ".spring.anchor");
    expect_bits(x.stiffness, y.stiffness, w + ".spring.stiffness");
    expect_bits(x.damping, y.damping, w + ".spring.damping");
    expect_bits(x.rest_length, y.rest_length, w + ".spring.rest_length");
  });
  expect_optional(
      a.constant_force, b.constant_force, w + ".force",
      [&](const auto& x, const auto& y) { expect_bits(x.force, y.force, w + ".force"); });
  expect_optional(a.gravity, b.gravity, w + ".gravity", [&](const auto& x, const auto& y) {
    expect_bits(x.acceleration, y.acceleration, w + ".gravity");
  });
  expect_optional(a.drag, b.drag, w + ".drag", [&](const auto& x, const auto& y) {
    expect_bits(x.coefficient, y.coefficient, w + ".drag");
  });
  expect_optional(a.appearance, b.appearance, w + ".appearance", [&](const auto& x, const auto& y) {
    expect_bits(x.radius, y.radius, w + ".appearance.radius");
    EXPECT_EQ(x.color, y.color) << w << ".appearance.color";
    EXPECT_EQ(x.sprite, y.sprite) << w << ".appearance.sprite";
    expect_bits(x.sprite_size, y.sprite_size, w + ".appearance.sprite_size");
  });
  expect_optional(a.collider, b.collider, w + ".collider", [&](const auto& x, const auto& y) {
    expect_bits(x.radius, y.radius, w + ".collider.radius");
    expect_bits(x.restitution, y.restitution, w + ".collider.restitution");
    expect_bits(x.friction, y.friction, w + ".collider.friction");
    EXPECT_EQ(x.collide, y.collide) << w << ".collider.collide";
  });
  expect_bits(a.inertia, b.inertia, w + ".inertia");
  expect_optional(a.mover, b.mover, w + ".mover", [&](const auto& x, const auto& y) {
    expect_bits(x.max_floor_angle, y.max_floor_angle, w + ".mover.max_floor_angle");
    expect_bits(x.step_height, y.step_height, w + ".mover.step_height");
    expect_bits(x.snap_distance, y.snap_distance, w + ".mover.snap_distance");
    expect_bits(x.push_force, y.push_force, w + ".mover.push_force");
    expect_bits(x.skin, y.skin, w + ".mover.skin");
  });
  ASSERT_EQ(a.shapes.size(), b.shapes.size()) << w << ".shapes";
  for (std::size_t i = 0; i < a.shapes.size(); ++i) {
    const ShapeDef &x = a.shapes[i], &y = b.shapes[i];
    const std::string s = w + ".shape[" + std::to_string(i) + "]";
    EXPECT_EQ(x.kind, y.kind) << s;
    expect_bits(x.radius, y.radius, s + ".radius");
    expect_bits(x.half_extents, y.half_extents, s + ".half_extents");
    ASSERT_EQ(x.count, y.count) << s << ".count";
    for (std::size_t k = 0; k < x.vertices.size(); ++k) {
      expect_bits(x.vertices[k], y.vertices[k], s + ".vertices[" + std::to_string(k) + "]");
    }
    expect_bits(x.offset, y.offset, s + ".offset");
    expect_bits(x.angle, y.angle, s + ".angle");
    expect_bits(x.density, y.density, s + ".density");
    expect_bits(x.friction, y.friction, s + ".friction");
    expect_bits(x.restitution, y.restitution, s + ".restitution");
    expect_bits(x.rolling_resistance, y.rolling_resistance, s + ".rolling_resistance");
    EXPECT_EQ(x.filter, y.filter) << s << ".filter";
    EXPECT_EQ(x.sensor, y.sensor) << s << ".sensor";
    EXPECT_EQ(x.color, y.color) << s << ".color";
    EXPECT_EQ(x.one_way, y.one_way) << s << ".one_way";
  }
}

/// Every field of a and b, doubles bit for bit, names and appearances included.
inline void expect_same_world(const WorldDef& a, const WorldDef& b) {
  EXPECT_EQ(a.precision, b.precision);
  const WorldSettings &s = a.settings, &t = b.settings;
  expect_bits(s.dt, t.dt, "dt");
  EXPECT_EQ(s.integrator, t.integrator);
  EXPECT_EQ(s.substeps, t.substeps);
  EXPECT_EQ(s.flush_denormals, t.flush_denormals);
  EXPECT_EQ(s.track_dissipation, t.track_dissipation);
  EXPECT_EQ(s.threads, t.threads);
  expect_optional(s.contacts, t.contacts, "contacts", [&](const auto& x, const auto& y) {
    expect_bits(x.restitution, y.restitution, "contacts.restitution");
    expect_bits(x.friction, y.friction, "contacts.friction");
    expect_bits(x.restitution_threshold, y.restitution_threshold, "contacts.restitution_threshold");
    EXPECT_EQ(x.velocity_iterations, y.velocity_iterations) << "contacts.velocity_iterations";
    EXPECT_EQ(x.position_iterations, y.position_iterations) << "contacts.position_iterations";
    EXPECT_EQ(x.rolling, y.rolling) << "contacts.rolling";
    EXPECT_EQ(x.sleep, y.sleep) << "contacts.sleep";
    expect_bits(x.sleep_speed, y.sleep_speed, "contacts.sleep_speed");
    expect_bits(x.sleep_time, y.sleep_time, "contacts.sleep_time");
  });
  ASSERT_EQ(a.bodies.size(), b.bodies.size());
  for (std::size_t i = 0; i < a.bodies.size(); ++i) {
    expect_same_body(a.bodies[i], b.bodies[i], "body[" + std::to_string(i) + "]");
  }
  ASSERT_EQ(a.links.size(), b.links.size());
  for (std::size_t i = 0; i < a.links.size(); ++i) {
    const std::string w = "link[" + std::to_string(i) + "]";
    EXPECT_EQ(a.links[i].body_a, b.links[i].body_a) << w;
    EXPECT_EQ(a.links[i].body_b, b.links[i].body_b) << w;
    expect_bits(a.links[i].spring.stiffness, b.links[i].spring.stiffness, w + ".stiffness");
    expect_bits(a.links[i].spring.damping, b.links[i].spring.damping, w + ".damping");
    expect_bits(a.links[i].spring.rest_length, b.links[i].spring.rest_length, w + ".rest_length");
  }
  ASSERT_EQ(a.planes.size(), b.planes.size());
  for (std::size_t i = 0; i < a.planes.size(); ++i) {
    const std::string w = "plane[" + std::to_string(i) + "]";
    expect_bits(a.planes[i].normal, b.planes[i].normal, w + ".normal");
    expect_bits(a.planes[i].offset, b.planes[i].offset, w + ".offset");
    expect_bits(a.planes[i].restitution, b.planes[i].restitution, w + ".restitution");
    expect_bits(a.planes[i].friction, b.planes[i].friction, w + ".friction");
  }
  ASSERT_EQ(a.segments.size(), b.segments.size());
  for (std::size_t i = 0; i < a.segments.size(); ++i) {
    const std::string w = "segment[" + std::to_string(i) + "]";
    const SegmentDef &x = a.segments[i], &y = b.segments[i];
    expect_bits(x.a, y.a, w + ".a");
    expect_bits(x.b, y.b, w + ".b");
    expect_bits(x.restitution, y.restitution, w + ".restitution");
    expect_bits(x.friction, y.friction, w + ".friction");
    ASSERT_EQ(x.prev.has_value(), y.prev.has_value()) << w << ".prev";
    if (x.prev) expect_bits(*x.prev, *y.prev, w + ".prev");
    ASSERT_EQ(x.next.has_value(), y.next.has_value()) << w << ".next";
    if (x.next) expect_bits(*x.next, *y.next, w + ".next");
    EXPECT_EQ(x.body, y.body) << w << ".body";
    EXPECT_EQ(x.color, y.color) << w << ".color";
    expect_bits(x.width, y.width, w + ".width");
    EXPECT_EQ(x.one_way, y.one_way) << w << ".one_way";
  }
  ASSERT_EQ(a.joints.size(), b.joints.size());
  for (std::size_t i = 0; i < a.joints.size(); ++i) {
    const std::string w = "joint[" + std::to_string(i) + "]";
    const JointDef &x = a.joints[i], &y = b.joints[i];
    EXPECT_EQ(x.type, y.type) << w << ".type";
    EXPECT_EQ(x.body_a, y.body_a) << w << ".body_a";
    EXPECT_EQ(x.body_b, y.body_b) << w << ".body_b";
    EXPECT_EQ(x.name, y.name) << w << ".name";
    expect_bits(x.anchor, y.anchor, w + ".anchor");
    expect_optional(x.anchor_b, y.anchor_b, w + ".anchor_b",
                    [&](Vec2 p, Vec2 q) { expect_bits(p, q, w + ".anchor_b"); });
    expect_bits(x.axis, y.axis, w + ".axis");
    expect_bits(x.length, y.length, w + ".length");
    expect_bits(x.lower, y.lower, w + ".lower");
    expect_bits(x.upper, y.upper, w + ".upper");
    expect_bits(x.motor_speed, y.motor_speed, w + ".motor_speed");
    expect_bits(x.max_motor_torque, y.max_motor_torque, w + ".max_motor_torque");
    expect_bits(x.max_motor_force, y.max_motor_force, w + ".max_motor_force");
    expect_bits(x.frequency, y.frequency, w + ".frequency");
    expect_bits(x.damping_ratio, y.damping_ratio, w + ".damping_ratio");
    expect_bits(x.target, y.target, w + ".target");
    expect_bits(x.break_force, y.break_force, w + ".break_force");
    expect_bits(x.break_torque, y.break_torque, w + ".break_torque");
    EXPECT_EQ(x.collide_connected, y.collide_connected) << w << ".collide_connected";
  }
}

}  // namespace fixstep::test
