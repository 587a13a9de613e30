// Bodies with shapes in the sleeping islands (ContactSettings::sleep; world_sleep.cpp has the
// islands themselves). A dynamic body with shapes counts its still ticks as a disc does, its
// speed and its rim's (ω times its farthest point from the centre of mass) below sleep_speed;
// its shape contacts and broadphase pairs join it to the island of what it touches, a moving
// kinematic body or carried segment it touches keeps that island awake, and asleep it is
// immovable (put back after the free step) and solved as a static body by the shape contacts.
// It wakes, with its island, when the shape broadphase pairs it with a moving body (an awake
// dynamic one, or a kinematic one in motion) and is then paired again, before any manifold is
// made (ShapeTick::wake), besides the input, edits and structural changes that wake any island.
#include <cmath>

#include "island_union.hpp"
#include "shape_world.hpp"
#include "world_kernel.hpp"

namespace fixstep {

template <class Real>
void detail::WorldKernel<Real>::mark_shape_sleepers() {
  ShapeWorld& w = *shape_world_;
  auto mark = [&](ShapedBody& b) {
    const bool asleep = asleep_[b.body] != 0;
    b.asleep = asleep;
    if (b.type != BodyType::dynamic) return;
    b.inv_mass = asleep ? 0.0 : 1.0 / mass_[b.body];
    const bool turns = !asleep && b.set != ShapedBody::none;
    b.inv_inertia = turns ? 1.0 / shape_sets_.data[b.set].inertia : 0.0;
  };
  if (w.rest_stale() && !w.rest_whole()) {  // the others are as the last marking left them
    for (const std::uint32_t i : w.flipped()) mark(w.bodies_[i]);
    return;
  }
  for (ShapedBody& b : w.bodies_) mark(b);
}

template <class Real>
void detail::WorldKernel<Real>::wake_shape_sleepers(void* kernel) {
  auto& k = *static_cast<WorldKernel*>(kernel);
  const ShapeWorld& w = *k.shape_world_;
  for (const std::uint32_t i : w.woken()) {
    const std::uint32_t j = w.bodies_[i].body;
    if (k.asleep_[j] != 0) k.wake_bodies_.push_back(j);
  }
  k.wake_labelled();
  k.mark_shape_sleepers();
}

template <class Real>
bool detail::WorldKernel<Real>::count_still_shapes(double speed2) {
  if (shape_sleepers_ == dynamic_shaped_) return false;  // every one asleep: none to count
  const ShapeWorld& w = *shape_world_;
  bool ready = false;
  for_shape_bodies([&](std::uint32_t i) {  // the awake ones are live
    const ShapedBody& b = w.bodies_[i];
    const std::uint32_t j = b.body;
    if (b.disc || b.type != BodyType::dynamic || asleep_[j] != 0) return;
    const double spin = shape_sets_.data[b.set].spin * b.extent;
    const double v2 =
        std::max(double(vx_[j]) * double(vx_[j]) + double(vy_[j]) * double(vy_[j]), spin * spin);
    std::uint32_t& still = still_ticks_[j];
    still = v2 < speed2 ? std::min(0xfffffffeu, still) + 1 : 0;
    ready = ready || still >= sleep_ticks_;
  });
  return ready;
}

template <class Real>
void detail::WorldKernel<Real>::join_shape_islands() {
  const ShapeWorld& w = *shape_world_;
  std::vector<std::uint32_t>& blocked = island_blocked_;
  const std::uint32_t stamp = blocked_stamp_;
  auto awake = [&](std::uint32_t j) { return types_[j] == BodyType::dynamic && asleep_[j] == 0; };
  auto moving = [&](std::uint32_t i) {  // a kinematic body of the shape world in motion
    const ShapedBody& b = w.bodies_[i];
    if (b.type != BodyType::kinematic) return false;
    const std::uint32_t j = b.body;
    const bool turns = b.set != ShapedBody::none && shape_sets_.data[b.set].spin != 0.0;
    return vx_[j] != Real(0) || vy_[j] != Real(0) || turns;
  };
  for (const ShapeRow& r : w.rows()) {
    const std::uint32_t b = w.bodies_[r.b].body;
    if (r.a == ShapeWorld::none) {  // a plane, or a segment a kinematic body may carry
      const auto high = static_cast<std::uint32_t>(r.pair >> 32);
      const bool segment = (high & 0xF0000000u) == 0xE0000000u;
      const Vec2 u = segment ? segments_.velocity(high & 0x0FFFFFFFu) : Vec2{};
      if (u.x != 0.0 || u.y != 0.0) blocked[b] = stamp;
      continue;
    }
    const std::uint32_t a = w.bodies_[r.a].body;
    const bool da = awake(a), db = awake(b);
    if (da && db) detail::join(island_parent_, a, b);
    if (da && moving(r.b)) blocked[a] = stamp;
    if (db && moving(r.a)) blocked[b] = stamp;
  }
  // Jointed bodies share an island (a joint to a moving kinematic body keeps its body awake).
  // (A joint whose two ends rest joins no awake body: ShapeWorld::live_joints.)
  for_shape_joints([&](const JointRecord& j, std::size_t) {
    if (j.a == JointRecord::none || j.b == JointRecord::none) return;
    const std::uint32_t a = w.bodies_[j.a].body, b = w.bodies_[j.b].body;
    const bool da = awake(a), db = awake(b);
    if (da && db) detail::join(island_parent_, a, b);
    if (da && moving(j.b)) blocked[a] = stamp;
    if (db && moving(j.a)) blocked[b] = stamp;
  });
  // Bodies the broadphase pairs share an island (as discs do; see join_islands).
  for (const ShapeWorld::Candidate& c : w.candidates()) {
    const std::uint32_t a = w.bodies_[w.shapes_[c.a].owner].body;
    const std::uint32_t b = w.bodies_[w.shapes_[c.b].owner].body;
    if (awake(a) && awake(b)) detail::join(island_parent_, a, b);
  }
}

template <class Real>
bool detail::WorldKernel<Real>::shapes_at_rest() const {
  if (shape_sleepers_ < dynamic_shaped_) return false;
  const ShapeWorld& w = *shape_world_;
  for (const std::uint32_t i : kinematic_shaped_) {
    const ShapedBody& b = w.bodies_[i];
    const std::uint32_t j = b.body;
    const bool turns = b.set != ShapedBody::none && shape_sets_.data[b.set].spin != 0.0;
    if (vx_[j] != Real(0) || vy_[j] != Real(0) || turns) return false;
  }
  return true;
}

template <class Real>
void detail::WorldKernel<Real>::count_shaped_bodies() {
  shaped_dynamic_.clear(), kinematic_shaped_.clear(), dynamic_shaped_ = 0;
  if (!sleep_ || !shape_world_) return;
  const ShapeWorld& w = *shape_world_;
  shaped_dynamic_.assign(body_count(), 0);
  for (std::uint32_t i = 0; i < w.bodies_.size(); ++i) {
    const ShapedBody& b = w.bodies_[i];
    if (b.type == BodyType::kinematic) kinematic_shaped_.push_back(i);  // a disc's too
    if (b.type == BodyType::dynamic && !b.disc && shaped_dynamic_[b.body] == 0) {
      shaped_dynamic_[b.body] = 1, ++dynamic_shaped_;
    }
  }
}

}  // namespace fixstep
