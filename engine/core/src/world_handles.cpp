// World's handle API: bodies and links named by Entity and Link, forwarded to the kernel
// inside (world_state.hpp), and the check of a tick's per-body input.
#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "fixstep/core/components.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/world.hpp"
#include "world_state.hpp"

namespace fixstep {

void World::destroy(Entity e) {
  visit([&](auto& w) { w.destroy(e); });
  queries_changed();
}
bool World::contains(Entity e) const {
  return visit([&](const auto& w) { return w.contains(e); });
}
void World::set_position(Entity e, Vec2 position) {
  visit([&](auto& w) { w.set_position(e, position); });
  queries_changed();
}

void World::set_velocity(Entity e, Vec2 velocity) {
  visit([&](auto& w) { w.set_velocity(e, velocity); });
}

std::span<const ShapeDef> World::shapes(Entity e) const {
  return visit([&](const auto& w) { return w.shapes(e); });
}

Vec2 World::local_center(Entity e) const {
  return visit([&](const auto& w) { return w.local_center(e); });
}

MoverState World::mover_state(Entity e) const {
  return visit([&](const auto& w) { return w.mover_state(e); });
}

std::uint64_t World::user_data(Entity e) const {
  return visit([&](const auto& w) { return w.user_data(e); });
}

void World::set_user_data(Entity e, std::uint64_t value) {
  visit([&](auto& w) { w.set_user_data(e, value); });
}

Entity World::find(std::string_view name) const {
  return visit([&](const auto& w) { return w.find(name); });
}
Body World::body(Entity e) const {
  return visit([&](const auto& w) { return w.body(e); });
}
void World::set_body(Entity e, const Body& body) {
  visit([&](auto& w) { w.set_body(e, body); });
  queries_changed();
}
const std::string& World::name(Entity e) const {
  return visit([&](const auto& w) -> const std::string& { return w.name(w.index_of(e)); });
}
BodyType World::type(Entity e) const {
  return visit([&](const auto& w) { return w.type(e); });
}
bool World::asleep(Entity e) const {
  return visit([&](const auto& w) { return w.asleep(w.index_of(e)); });
}
void World::wake(Entity e) {
  visit([&](auto& w) { w.wake(w.index_of(e)); });
}
std::size_t World::index_of(Entity e) const {
  return visit([&](const auto& w) { return w.index_of(e); });
}
void World::destroy_link(Link link) {
  visit([&](auto& w) { w.destroy_link(link); });
}
bool World::contains(Link link) const {
  return visit([&](const auto& w) { return w.contains(link); });
}
LinkDef World::link(Link link) const {
  return visit([&](const auto& w) { return w.link(link); });
}
std::span<const ContactEvent> World::contacts_begun() const {
  return visit([](const auto& w) { return w.contacts_begun(); });
}
std::span<const ContactEvent> World::contacts_ended() const {
  return visit([](const auto& w) { return w.contacts_ended(); });
}
std::span<const SensorEvent> World::sensors_begun() const {
  return visit([](const auto& w) { return w.sensors_begun(); });
}
std::span<const SensorEvent> World::sensors_ended() const {
  return visit([](const auto& w) { return w.sensors_ended(); });
}
std::span<const SensorEvent> World::sensor_overlaps() const {
  return visit([](const auto& w) { return w.sensor_overlaps(); });
}

void World::check_body_input(const BodyInput& in, const std::string& who) const {
  const BodyType t = type(in.body);
  const bool angular = in.kind >= BodyInputKind::torque;
  if (angular && in.value.y != 0.0) {
    throw std::invalid_argument(fmt::format("{}: an angular input's value is [x, 0] (got [{}, {}])",
                                            who, in.value.x, in.value.y));
  }
  if (angular && shapes(in.body).empty()) {
    throw std::invalid_argument(
        fmt::format("{} ('{}'): angular input turns bodies with shapes only", who, name(in.body)));
  }
  const bool kinematic_kind = in.kind == BodyInputKind::velocity ||
                              in.kind == BodyInputKind::angular_velocity ||
                              in.kind == BodyInputKind::target_angle;
  if (kinematic_kind && t != BodyType::kinematic) {
    throw std::invalid_argument(fmt::format(
        "{} ('{}'): a {} input moves kinematic bodies only; push a dynamic body with {}", who,
        name(in.body), angular ? "turning" : "velocity",
        angular ? "a torque or an angular impulse" : "a force or an impulse"));
  }
  if (!kinematic_kind && t != BodyType::dynamic) {
    throw std::invalid_argument(fmt::format(
        "{} ('{}'): {} move dynamic bodies only (a {} body {})", who, name(in.body),
        angular ? "torques and angular impulses" : "forces and impulses",
        t == BodyType::kinematic ? "kinematic" : "static",
        t == BodyType::kinematic ? "moves at its velocity: give it one" : "never moves"));
  }
}

void World::check_input(const TickInput& input) const {
  if (input.bodies.size() > max_body_inputs) {
    throw std::invalid_argument(fmt::format("tick {}: {} per-body inputs; at most {} per tick",
                                            input.tick, input.bodies.size(), max_body_inputs));
  }
  for (std::size_t i = 0; i < input.bodies.size(); ++i) {
    const BodyInput& in = input.bodies[i];
    const std::string who =
        fmt::format("tick {}: {} on body {}:{}", input.tick, body_input_kind_name(in.kind),
                    in.body.index1, in.body.generation);
    if (!contains(in.body)) {
      throw std::invalid_argument(who + ": no such body (null, or destroyed)");
    }
    if (!std::isfinite(in.value.x) || !std::isfinite(in.value.y)) {
      throw std::invalid_argument(
          fmt::format("{}: must be finite (got [{}, {}])", who, in.value.x, in.value.y));
    }
    check_body_input(in, who);
  }
  if (!input.joints.empty()) check_joint_inputs(input);  // world_joint_handles.cpp
}

}  // namespace fixstep
