// A world's energy account (kinetic, the potentials of its force terms and links, and what
// contacts and damping dissipated) and its state hash, the bits that determinism is checked by.
#include <cstdint>
#include <span>

#include "fixstep/core/bits.hpp"
#include "fixstep/core/components.hpp"
#include "fixstep/core/fnv1a.hpp"
#include "fixstep/core/step_results.hpp"
#include "world_kernel.hpp"

namespace fixstep {

template <class Real>
double detail::WorldKernel<Real>::dissipated_energy() const {
  double total = dissipated_gone_;
  for (std::size_t j = 0; j < body_count(); ++j) {
    total += mass_[j] * double(dissipated_body_[j]);
  }
  for (const Real e : dissipated_link_) total += double(e);
  return total;
}

// Calls add(body index, kind, J) for every energy contribution: kinetic ½m|v|² per body, then
// each potential (see EnergyReport). Shared by energy() and body_energies().
template <class Real>
template <class Add>
void detail::WorldKernel<Real>::for_each_energy(Add&& add) const {
  // Static and kinematic bodies are outside the account (their motion is imposed).
  auto dynamic = [this](std::size_t j) { return types_[j] == BodyType::dynamic; };
  for (std::size_t j = 0; j < body_count(); ++j) {
    if (!dynamic(j)) continue;
    const double vx = vx_[j], vy = vy_[j];
    add(j, &EnergyReport::kinetic, 0.5 * mass_[j] * (vx * vx + vy * vy));
  }
  if (rolling_) {  // rotational ½ I ω² of rolling discs
    for (std::size_t i = 0; i < colliders_.data.size(); ++i) {
      const std::size_t j = bodies_.index(colliders_.set.dense[i]);
      if (!dynamic(j)) continue;
      const double w = spin_[j];
      add(j, &EnergyReport::kinetic, 0.5 * inertia_of(mass_[j], colliders_.data[i]) * w * w);
    }
  }
  for (std::size_t i = 0; i < shape_sets_.data.size(); ++i) {  // ½ I ω² of bodies with shapes
    const std::size_t j = bodies_.index(shape_sets_.set.dense[i]);
    if (!dynamic(j)) continue;
    const ShapeSet& set = shape_sets_.data[i];
    add(j, &EnergyReport::kinetic, 0.5 * set.inertia * set.spin * set.spin);
  }
  for (std::size_t i = 0; i < springs_.data.size(); ++i) {
    const SpringDamper& s = springs_.data[i];
    const std::size_t j = bodies_.index(springs_.set.dense[i]);
    if (!dynamic(j)) continue;
    const double dx = double(x_[j]) - s.anchor.x, dy = double(y_[j]) - s.anchor.y;
    const double d2 = dx * dx + dy * dy;
    const double stretch = std::sqrt(d2) - s.rest_length;
    add(j, &EnergyReport::spring,
        0.5 * s.stiffness * (s.rest_length == 0.0 ? d2 : stretch * stretch));
  }
  for (const LinkDef& l : link_defs_) {
    const std::size_t a = bodies_.index(l.body_a), b = bodies_.index(l.body_b);
    const double dx = double(x_[a]) - double(x_[b]), dy = double(y_[a]) - double(y_[b]);
    const double d2 = dx * dx + dy * dy;
    const double stretch = std::sqrt(d2) - l.spring.rest_length;
    const double e =
        0.5 * l.spring.stiffness * (l.spring.rest_length == 0.0 ? d2 : stretch * stretch);
    add(a, &EnergyReport::spring, 0.5 * e);
    add(b, &EnergyReport::spring, 0.5 * e);
  }
  for (std::size_t i = 0; i < gravities_.data.size(); ++i) {
    const Vec2 g = gravities_.data[i].acceleration;
    const std::size_t j = bodies_.index(gravities_.set.dense[i]);
    if (!dynamic(j)) continue;
    add(j, &EnergyReport::gravity, -mass_[j] * (g.x * double(x_[j]) + g.y * double(y_[j])));
  }
  for (std::size_t i = 0; i < constant_forces_.data.size(); ++i) {
    const Vec2 f = constant_forces_.data[i].force;
    const std::size_t j = bodies_.index(constant_forces_.set.dense[i]);
    if (!dynamic(j)) continue;
    add(j, &EnergyReport::constant_force, -(f.x * double(x_[j]) + f.y * double(y_[j])));
  }
}

template <class Real>
void detail::WorldKernel<Real>::body_energies(std::span<double> out) const {
  if (out.size() < body_count())
    throw std::invalid_argument("World::body_energies: span too short");
  std::fill_n(out.begin(), body_count(), 0.0);
  for_each_energy([&](std::size_t j, double EnergyReport::*, double joules) { out[j] += joules; });
}

template <class Real>
EnergyReport detail::WorldKernel<Real>::energy() const {
  EnergyReport e;
  for_each_energy(
      [&](std::size_t, double EnergyReport::*kind, double joules) { e.*kind += joules; });
  return e;
}

template <class Real>
std::uint64_t detail::WorldKernel<Real>::state_hash() const {
  // FNV-1a (fnv1a.hpp) of each value's bytes, least significant first (what memory holds on
  // every platform fixstep runs on: x86-64, aarch64, wasm32).
  std::uint64_t h = fnv1a_basis;
  auto mix_bytes = [&h](std::uint64_t bits, std::size_t bytes) {
    for (std::size_t i = 0; i < bytes; ++i) h = fnv1a_byte(h, (bits >> (8 * i)) & 0xffu);
  };
  auto mix = [&](Real v) { mix_bytes(bits_of(v), sizeof(Real)); };
  for (std::size_t j = 0; j < body_count(); ++j) {
    mix(x_[j]);
    mix(y_[j]);
    mix(vx_[j]);
    mix(vy_[j]);
  }
  // Rolling discs (only in worlds that ask: every other world hashes as before).
  for (std::size_t j = 0; j < angle_.size(); ++j) mix(angle_[j]), mix(spin_[j]);
  // Bodies with shapes (only in worlds that have them), in their store's order.
  for (const ShapeSet& set : shape_sets_.data) {
    mix(static_cast<Real>(set.angle)), mix(static_cast<Real>(set.spin));
  }
  // Sleeping islands (only in worlds that ask), as the bytes of two 32-bit counts.
  for (std::size_t j = 0; j < asleep_.size(); ++j) {
    mix_bytes(still_ticks_[j], sizeof(std::uint32_t)), mix_bytes(asleep_[j], sizeof(std::uint32_t));
  }
  // Joints (only in worlds that have them): what input set and the impulses they carry to the
  // next tick, in double, and whether each broke.
  for (const JointRecord& j : joint_records_) {
    auto mix_double = [&](double v) { mix_bytes(bits_of(v), 8); };
    const JointImpulses& im = j.impulses;
    for (const double v :
         {im.linear.x, im.linear.y, im.angular, im.spring, im.motor, im.lower, im.upper, im.axial,
          j.motor_speed, j.max_torque, j.max_force, j.target.x, j.target.y, j.target_angle}) {
      mix_double(v);
    }
    mix_bytes(std::uint64_t{j.motor_on} | std::uint64_t{j.broken} << 1, 1);
  }
  // Movers (only in worlds that have them): what the last tick met, which the next one reads.
  for (const MoverRecord& m : movers_.data) {
    const MoverState& s = m.state;
    mix_bytes(std::uint64_t{s.on_floor} | std::uint64_t{s.on_wall} << 1 |
                  std::uint64_t{s.on_ceiling} << 2,
              1);
    for (const double v : {s.floor_normal.x, s.floor_normal.y, s.wall_normal.x, s.wall_normal.y,
                           s.displacement.x, s.displacement.y}) {
      mix_bytes(bits_of(v), 8);
    }
    mix_bytes(s.floor_body.index1, 4), mix_bytes(s.floor_body.generation, 4);
  }
  return h;
}

}  // namespace fixstep
