#include "world_kernel.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "fixstep/core/bits.hpp"
#include "fixstep/core/components.hpp"
#include "fixstep/core/float_mode.hpp"
#include "fixstep/core/fnv1a.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/value_ranges.hpp"
#include "fixstep/core/world_settings.hpp"
#include "shape_world.hpp"
#include "value_checks.hpp"

namespace fixstep {

namespace {

/// Swap-and-pop element i of every array in the pack (keeps SoA arrays aligned).
template <class... Vs>
void swap_pop(std::size_t i, Vs&... vs) {
  ((vs[i] = std::move(vs.back()), vs.pop_back()), ...);
}

}  // namespace

template <class Real>
detail::WorldKernel<Real>::WorldKernel(const WorldSettings& settings) : settings_(settings) {
  if (!representable<Real>(settings.dt) || settings.dt <= 0.0) {
    throw std::invalid_argument(
        fmt::format("world: dt must be finite and > 0 s (got {})", settings.dt));
  }
  if (settings.substeps < 1) {
    throw std::invalid_argument(
        fmt::format("world: substeps must be >= 1 (got {})", settings.substeps));
  }
  if (const auto& c = settings.contacts) {
    constexpr int most = ContactSettings::max_iterations;
    if (c->velocity_iterations < 1 || c->velocity_iterations > most) {
      throw std::invalid_argument(
          fmt::format("world: contacts.velocity_iterations must be in [1, {}] (got {})", most,
                      c->velocity_iterations));
    }
    if (c->position_iterations < 0 || c->position_iterations > most) {
      throw std::invalid_argument(
          fmt::format("world: contacts.position_iterations must be in [0, {}] (got {})", most,
                      c->position_iterations));
    }
    if (!(std::isfinite(c->restitution) && c->restitution >= 0.0 && c->restitution <= 1.0)) {
      throw std::invalid_argument(
          fmt::format("world: contacts.restitution must be in [0, 1] (got {})", c->restitution));
    }
    if (!(std::isfinite(c->restitution_threshold) && c->restitution_threshold >= 0.0)) {
      throw std::invalid_argument(
          fmt::format("world: contacts.restitution_threshold must be finite and >= 0 m/s (got {})",
                      c->restitution_threshold));
    }
    if (!(nonnegative_coefficient(c->friction))) {  // √(μa μb) and μ·P stay finite
      throw std::invalid_argument(
          fmt::format("world: contacts.friction must be in [0, 1e100] (got {})", c->friction));
    }
    rolling_ = c->rolling;
    sleep_ = c->sleep;
    if (sleep_) sleep_ticks_ = sleep_ticks(*c, settings.dt);
  }
}

template <class Real>
std::string detail::WorldKernel<Real>::describe(Entity e) const {
  if (bodies_.contains(e)) {
    const auto& n = names_[bodies_.index(e)];
    if (!n.empty()) return fmt::format("body '{}'", n);
  }
  return fmt::format("entity {}:{}", e.index1, e.generation);
}

template <class Real>
void detail::WorldKernel<Real>::require(Entity e) const {
  if (!bodies_.contains(e)) {
    throw std::invalid_argument(
        fmt::format("entity {}:{} is null or was destroyed", e.index1, e.generation));
  }
}

template <class Real>
void detail::WorldKernel<Real>::index_name(Entity e, const std::string& name) const {
  if (name_index_ && !name.empty()) name_index_->by_hash[fnv1a(name)].push_back(e);
}

template <class Real>
void detail::WorldKernel<Real>::unindex_name(Entity e, const std::string& name) const {
  if (!name_index_ || name.empty()) return;
  const auto it = name_index_->by_hash.find(fnv1a(name));
  if (it == name_index_->by_hash.end()) return;
  std::erase(it->second, e);
  if (it->second.empty()) name_index_->by_hash.erase(it);
}

template <class Real>
Entity detail::WorldKernel<Real>::find(std::string_view name) const {
  if (name.empty()) return null_entity;
  if (!name_index_) {
    name_index_.reset(new NameIndex);
    for (std::size_t j = 0; j < names_.size(); ++j) index_name(bodies_.dense[j], names_[j]);
  }
  const auto it = name_index_->by_hash.find(fnv1a(name));
  if (it == name_index_->by_hash.end()) return null_entity;
  Entity best = null_entity;
  std::size_t best_index = 0;
  for (const Entity e : it->second) {  // bodies of that hash: the first in dense order
    const std::size_t j = bodies_.index(e);
    if (names_[j] == name && (best == null_entity || j < best_index)) best = e, best_index = j;
  }
  return best;
}

template <class Real>
std::size_t detail::WorldKernel<Real>::index_of(Entity e) const {
  require(e);
  return bodies_.index(e);
}

template <class Real>
Entity detail::WorldKernel<Real>::create_body(const BodyDef& def) {
  const IeeeFloatMode ieee;  // a state never depends on the caller's FPU mode (float_mode.hpp)
  const std::string who = def.name.empty() ? std::string("body") : "body '" + def.name + "'";
  validate(def.body, who);
  if (def.spring) validate_component(*def.spring, who);
  if (def.constant_force) validate_component(*def.constant_force, who);
  if (def.gravity) validate_component(*def.gravity, who);
  if (def.drag) validate_component(*def.drag, who);
  if (def.appearance) validate_component(*def.appearance, who);
  if (def.collider) validate_component(*def.collider, who), check_sensor(*def.collider, who);
  check_shapes(def, who);  // world_shapes.cpp
  check_mover(def, who);   // world_movers.cpp

  Entity e;
  if (!free_slots_.empty()) {
    const std::uint32_t slot = free_slots_.back();
    free_slots_.pop_back();
    e = Entity{slot + 1, generations_[slot]};
  } else {
    generations_.push_back(1);
    e = Entity{static_cast<std::uint32_t>(generations_.size()), 1};
  }
  bodies_.insert(e);
  mass_.push_back(def.body.mass);
  types_.push_back(def.type);
  x_.push_back(static_cast<Real>(def.body.position.x));
  y_.push_back(static_cast<Real>(def.body.position.y));
  // A static body rests (the free step leaves it alone): its velocity is zero from the start.
  const bool rests = def.type == BodyType::static_body;
  vx_.push_back(rests ? Real(0) : static_cast<Real>(def.body.velocity.x));
  vy_.push_back(rests ? Real(0) : static_cast<Real>(def.body.velocity.y));
  prev_x_.push_back(x_.back());
  prev_y_.push_back(y_.back());
  names_.push_back(def.name);
  user_data_.push_back(def.user_data);
  index_name(e, def.name);
  dissipated_body_.push_back(Real(0));
  if (rolling_) {
    angle_.push_back(static_cast<Real>(std::remainder(def.body.angle, 2.0 * std::numbers::pi)));
    spin_.push_back(static_cast<Real>(def.body.angular_velocity));
    inv_inertia_.push_back(0.0);
  }
  if (sleep_) still_ticks_.push_back(0), asleep_.push_back(0);

  if (def.spring) set(e, *def.spring);
  if (def.constant_force) set(e, *def.constant_force);
  if (def.gravity) set(e, *def.gravity);
  if (def.drag) set(e, *def.drag);
  if (def.appearance) set(e, *def.appearance);
  if (def.collider) set(e, *def.collider);
  if (!def.shapes.empty()) add_shapes(e, def, who);
  if (def.mover) {
    movers_.set.insert(e);
    movers_.data.push_back(MoverRecord{*def.mover, MoverState{}, def.body.position});
  }
  terms_dirty_ = true;
  return e;
}

template <class Real>
void detail::WorldKernel<Real>::destroy(Entity e) {
  require(e);
  // Links and joints attached to e go first (Box2D destroys a body's joints with it).
  for (std::size_t i = link_defs_.size(); i-- > 0;) {
    if (link_defs_[i].body_a == e || link_defs_[i].body_b == e) destroy_link(link_at(i));
  }
  if (!joint_records_.empty()) destroy_joints_of(e);  // world_joints.cpp
  remove<SpringDamper>(e);
  remove<ConstantForce>(e);
  remove<Gravity>(e);
  remove<LinearDrag>(e);
  remove<Appearance>(e);
  remove<Collider>(e);
  remove_shapes(e);
  if (movers_.set.contains(e)) {
    const std::size_t m = movers_.set.erase(e);
    if (m + 1 != movers_.data.size()) movers_.data[m] = movers_.data.back();
    movers_.data.pop_back();
  }
  unindex_name(e, names_[bodies_.index(e)]);
  const std::size_t i = bodies_.erase(e);
  dissipated_gone_ += mass_[i] * double(dissipated_body_[i]);  // stays in the account
  swap_pop(i, x_, y_, vx_, vy_, prev_x_, prev_y_, mass_, types_, names_, user_data_,
           dissipated_body_);
  if (rolling_) swap_pop(i, angle_, spin_, inv_inertia_);
  if (sleep_) swap_pop(i, still_ticks_, asleep_);  // every island wakes at the rebuild
  ++generations_[e.slot()];
  free_slots_.push_back(e.slot());
  terms_dirty_ = true;
}

template <class Real>
Link detail::WorldKernel<Real>::create_link(const LinkDef& def) {
  const IeeeFloatMode ieee;  // a state never depends on the caller's FPU mode (float_mode.hpp)
  validate_link(def, "link");
  Entity key;
  if (!link_free_slots_.empty()) {
    const std::uint32_t slot = link_free_slots_.back();
    link_free_slots_.pop_back();
    key = Entity{slot + 1, link_generations_[slot]};
  } else {
    link_generations_.push_back(1);
    key = Entity{static_cast<std::uint32_t>(link_generations_.size()), 1};
  }
  links_.insert(key);
  link_defs_.push_back(def);
  dissipated_link_.push_back(Real(0));
  terms_dirty_ = true;
  return Link{key.index1, key.generation};
}

template <class Real>
bool detail::WorldKernel<Real>::contains(Link link) const {
  return links_.contains(Entity{link.index1, link.generation});
}

template <class Real>
void detail::WorldKernel<Real>::destroy_link(Link link) {
  const Entity key{link.index1, link.generation};
  if (!links_.contains(key)) {
    throw std::invalid_argument(
        fmt::format("link {}:{} is null or was destroyed", link.index1, link.generation));
  }
  const std::size_t i = links_.erase(key);
  dissipated_gone_ += double(dissipated_link_[i]);  // stays in the account
  swap_pop(i, link_defs_, dissipated_link_);
  ++link_generations_[key.slot()];
  link_free_slots_.push_back(key.slot());
  terms_dirty_ = true;
}

template <class Real>
LinkDef detail::WorldKernel<Real>::link(Link link) const {
  const Entity key{link.index1, link.generation};
  if (!links_.contains(key)) {
    throw std::invalid_argument(
        fmt::format("link {}:{} is null or was destroyed", link.index1, link.generation));
  }
  return link_defs_[links_.index(key)];
}

template <class Real>
std::pair<std::size_t, std::size_t> detail::WorldKernel<Real>::link_bodies(std::size_t i) const {
  return {bodies_.index(link_defs_[i].body_a), bodies_.index(link_defs_[i].body_b)};
}

template <class Real>
Body detail::WorldKernel<Real>::body(Entity e) const {
  const std::size_t i = index_of(e);
  Body b{mass_[i], {double(x_[i]), double(y_[i])}, {double(vx_[i]), double(vy_[i])}};
  if (rolling_) b.angle = double(angle_[i]), b.angular_velocity = double(spin_[i]);
  if (shape_sets_.set.contains(e)) {  // the origin, where the centre of mass lies off it
    const ShapeSet& set = shape_sets_.data[shape_sets_.set.index(e)];
    b.angle = set.angle, b.angular_velocity = set.spin;
    b.position = b.position - rotate(rot_of(set.angle), set.center);
  }
  return b;
}

template <class Real>
void detail::WorldKernel<Real>::set_body(Entity e, const Body& b) {
  const IeeeFloatMode ieee;  // a state never depends on the caller's FPU mode (float_mode.hpp)
  const std::size_t i = index_of(e);
  validate(b, describe(e));
  mass_[i] = b.mass;
  x_[i] = prev_x_[i] = static_cast<Real>(b.position.x);
  y_[i] = prev_y_[i] = static_cast<Real>(b.position.y);
  const bool rests = types_[i] == BodyType::static_body;  // its velocity zero (create_body)
  vx_[i] = rests ? Real(0) : static_cast<Real>(b.velocity.x);
  vy_[i] = rests ? Real(0) : static_cast<Real>(b.velocity.y);
  if (rolling_) {
    angle_[i] = static_cast<Real>(std::remainder(b.angle, 2.0 * std::numbers::pi));
    spin_[i] = static_cast<Real>(b.angular_velocity);
  }
  if (shape_sets_.set.contains(e)) {
    ShapeSet& set = shape_sets_.data[shape_sets_.set.index(e)];
    set.angle = rounded_to<Real>(std::remainder(b.angle, 2.0 * std::numbers::pi));
    set.spin = types_[i] == BodyType::static_body ? 0.0 : rounded_to<Real>(b.angular_velocity);
    const Vec2 c = b.position + rotate(rot_of(set.angle), set.center);
    x_[i] = prev_x_[i] = static_cast<Real>(c.x);
    y_[i] = prev_y_[i] = static_cast<Real>(c.y);
  }
  if (segments_.moves()) place_segments();
  unsettle_shapes();
  terms_dirty_ = true;  // 1/m enters the per-body coefficients
}

template <class Real>
void detail::WorldKernel<Real>::set_position(Entity e, Vec2 position) {
  const IeeeFloatMode ieee;
  const std::size_t i = index_of(e);
  check_vec<Real>(position, describe(e), "position");
  x_[i] = prev_x_[i] = static_cast<Real>(position.x);
  y_[i] = prev_y_[i] = static_cast<Real>(position.y);
  if (sleep_) wake(i);
  if (shape_world_) shape_world_->unsettle_body(static_cast<std::uint32_t>(i));
  if (segments_.moves()) place_segments();
}

template <class Real>
void detail::WorldKernel<Real>::set_velocity(Entity e, Vec2 velocity) {
  const IeeeFloatMode ieee;
  const std::size_t i = index_of(e);
  check_vec<Real>(velocity, describe(e), "velocity");
  if (types_[i] == BodyType::static_body && (velocity.x != 0.0 || velocity.y != 0.0)) {
    throw std::invalid_argument(
        fmt::format("{}: velocity: a static body never moves (got ({}, {}) m/s); make it kinematic",
                    describe(e), velocity.x, velocity.y));
  }
  const bool rests = types_[i] == BodyType::static_body;  // (-0.0 kept as 0: create_body)
  vx_[i] = rests ? Real(0) : static_cast<Real>(velocity.x);
  vy_[i] = rests ? Real(0) : static_cast<Real>(velocity.y);
  if (sleep_) wake(i);
  if (shape_world_) shape_world_->unsettle_body(static_cast<std::uint32_t>(i));
  if (segments_.moves()) place_segments();
}

template <class Real>
void detail::WorldKernel<Real>::set_keep_previous(bool keep) {
  keep_previous_ = keep;
  prev_x_ = x_;
  prev_y_ = y_;
}

template <class Real>
void detail::WorldKernel<Real>::reserve(std::size_t bodies) {
  bodies_.dense.reserve(bodies);
  bodies_.sparse.reserve(bodies);
  generations_.reserve(bodies);
  for (auto* v : {&x_, &y_, &vx_, &vy_, &prev_x_, &prev_y_}) v->reserve(bodies);
  mass_.reserve(bodies);
  types_.reserve(bodies);
  names_.reserve(bodies);
  user_data_.reserve(bodies);
}

template <class Real>
void detail::WorldKernel<Real>::rebuild_terms() {
  const IeeeFloatMode ieee;  // a state never depends on the caller's FPU mode (float_mode.hpp)
  // Per-body coefficients, summed in double and rounded once to Real.
  struct Field {
    double stiffness = 0, anchor_x = 0, anchor_y = 0, rest = 0, gamma = 0, cx = 0, cy = 0;
  };
  const std::size_t n = body_count();
  std::vector<Field> f(n);
  for (std::size_t i = 0; i < springs_.data.size(); ++i) {
    const SpringDamper& s = springs_.data[i];
    const std::size_t j = bodies_.index(springs_.set.dense[i]);
    if (types_[j] != BodyType::dynamic) continue;  // moved by nothing but its velocity
    Field& fj = f[j];
    const double m = mass_[j];
    fj.stiffness = s.stiffness / m;
    fj.gamma += s.damping / m;
    fj.anchor_x = s.anchor.x, fj.anchor_y = s.anchor.y, fj.rest = s.rest_length;
  }
  for (std::size_t i = 0; i < drags_.data.size(); ++i) {
    const std::size_t j = bodies_.index(drags_.set.dense[i]);
    if (types_[j] != BodyType::dynamic) continue;
    f[j].gamma += drags_.data[i].coefficient / mass_[j];
  }
  for (std::size_t i = 0; i < constant_forces_.data.size(); ++i) {
    const std::size_t j = bodies_.index(constant_forces_.set.dense[i]);
    if (types_[j] != BodyType::dynamic) continue;
    f[j].cx += constant_forces_.data[i].force.x / mass_[j];
    f[j].cy += constant_forces_.data[i].force.y / mass_[j];
  }
  for (std::size_t i = 0; i < gravities_.data.size(); ++i) {
    const std::size_t j = bodies_.index(gravities_.set.dense[i]);
    if (types_[j] != BodyType::dynamic) continue;
    f[j].cx += gravities_.data[i].acceleration.x;
    f[j].cy += gravities_.data[i].acceleration.y;
  }
  Coefficients& c = coeff_;
  auto to_real = [&](std::vector<Real>& out, double Field::*member) {
    out.resize(n);
    for (std::size_t j = 0; j < n; ++j) out[j] = static_cast<Real>(f[j].*member);
  };
  to_real(c.stiffness, &Field::stiffness);
  to_real(c.anchor_x, &Field::anchor_x);
  to_real(c.anchor_y, &Field::anchor_y);
  to_real(c.rest, &Field::rest);
  to_real(c.gamma, &Field::gamma);
  to_real(c.accel_x, &Field::cx);
  to_real(c.accel_y, &Field::cy);
  c.spring = !springs_.data.empty();
  c.rest_length = std::any_of(c.rest.begin(), c.rest.end(), [](Real r) { return r != Real(0); });
  c.damping = std::any_of(c.gamma.begin(), c.gamma.end(), [](Real g) { return g != Real(0); });
  // The same bits, not only equal values (+0 and -0 are equal), so that the fused sweep's one
  // value is every body's own.
  c.gamma_uniform = std::all_of(c.gamma.begin(), c.gamma.end(),
                                [&](Real g) { return same_bits(g, c.gamma.front()); });
  c.accel = false;
  for (std::size_t j = 0; j < n; ++j) c.accel = c.accel || c.accel_x[j] != 0 || c.accel_y[j] != 0;
  flows_.clear();
  rebuild_network();
  if (rolling_) rebuild_inertia();
  rebuild_contacts();
  if (sleep_) reset_sleep();  // a structural change wakes every island
  rebuild_discs();
  rebuild_shapes();       // world_shapes.cpp
  count_shaped_bodies();  // world_shape_sleep.cpp
  rebuild_joints();       // world_joints.cpp
  terms_dirty_ = false;
}

template <class Real>
unsigned detail::WorldKernel<Real>::active_terms() const {
  unsigned bits = 0;
  if (!springs_.data.empty()) bits |= term_spring;
  if (!constant_forces_.data.empty()) bits |= term_constant_force;
  if (!gravities_.data.empty()) bits |= term_gravity;
  if (!drags_.data.empty()) bits |= term_drag;
  if (!link_defs_.empty()) bits |= term_link;
  return bits;
}

// Force evaluation and the integrators are in world_step.cpp, instantiated there.

}  // namespace fixstep
