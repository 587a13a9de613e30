// A tick's input (TickInput), applied in two places of the tick and nowhere else: at its start
// (apply_input: islands woken, impulses and kinematic velocities, carried segments placed, the
// pointer's drag) and around its integration (integrate_with_input: per-body forces and the
// push for the tick's duration, put back after it).
#include <algorithm>
#include <cmath>

#include "world_kernel.hpp"

namespace fixstep {

namespace {

bool finite(Vec2 v) {
  return std::isfinite(v.x) && std::isfinite(v.y);
}

}  // namespace

template <class Real>
void detail::WorldKernel<Real>::apply_body_inputs(const TickInput& input) {
  for (const BodyInput& in : input.bodies) {
    if (in.kind == BodyInputKind::force || !bodies_.contains(in.body) || !finite(in.value)) {
      continue;
    }
    const std::size_t j = bodies_.index(in.body);
    if (in.kind == BodyInputKind::impulse && types_[j] == BodyType::dynamic) {
      // Δv = J/m, in double, rounded once to Real.
      vx_[j] = static_cast<Real>(double(vx_[j]) + in.value.x / mass_[j]);
      vy_[j] = static_cast<Real>(double(vy_[j]) + in.value.y / mass_[j]);
    } else if (in.kind == BodyInputKind::velocity && types_[j] == BodyType::kinematic) {
      vx_[j] = static_cast<Real>(in.value.x);
      vy_[j] = static_cast<Real>(in.value.y);
    } else if (in.kind >= BodyInputKind::torque) {
      apply_angular_input(in, j);  // world_shapes.cpp
    }
  }
}

// A force F on body j for one tick is a constant acceleration F/m added to the body's own
// (gravity + ConstantForce/m) in every stage of the integrator: the coefficient the fused
// sweep and the link passes read (coeff_.accel_x/y), and the implicit solver's copy when the
// tick solves a network implicitly. The previous values are saved and put back after the tick
// bit for bit, so the next tick without the force steps as if it had never been there.
template <class Real>
bool detail::WorldKernel<Real>::add_input_forces(const TickInput& input) {
  saved_accel_.clear();
  const bool implicit = settings_.integrator == Integrator::implicit_euler && !net_.a.empty();
  std::pair<double*, double*> solver{nullptr, nullptr};
  for (const BodyInput& in : input.bodies) {
    if (in.kind != BodyInputKind::force || !bodies_.contains(in.body) || !finite(in.value)) {
      continue;
    }
    const auto j = static_cast<std::uint32_t>(bodies_.index(in.body));
    if (types_[j] != BodyType::dynamic) continue;
    if (implicit && !solver.first) solver = implicit_accelerations();
    SavedAccel saved{j, coeff_.accel_x[j], coeff_.accel_y[j], 0.0, 0.0};
    const double ax = in.value.x / mass_[j], ay = in.value.y / mass_[j];
    coeff_.accel_x[j] = static_cast<Real>(double(coeff_.accel_x[j]) + ax);
    coeff_.accel_y[j] = static_cast<Real>(double(coeff_.accel_y[j]) + ay);
    if (solver.first) {
      saved.cx = solver.first[j], saved.cy = solver.second[j];
      solver.first[j] += ax, solver.second[j] += ay;
    }
    saved_accel_.push_back(saved);
  }
  if (saved_accel_.empty()) return false;
  saved_accel_flag_ = coeff_.accel;
  coeff_.accel = true;
  return true;
}

template <class Real>
void detail::WorldKernel<Real>::remove_input_forces() {
  const bool implicit = settings_.integrator == Integrator::implicit_euler && !net_.a.empty();
  const std::pair<double*, double*> solver =
      implicit ? implicit_accelerations() : std::pair<double*, double*>{nullptr, nullptr};
  // In reverse, so a body given two forces gets its first saved value back.
  for (auto it = saved_accel_.rbegin(); it != saved_accel_.rend(); ++it) {
    coeff_.accel_x[it->body] = it->ax, coeff_.accel_y[it->body] = it->ay;
    if (solver.first) solver.first[it->body] = it->cx, solver.second[it->body] = it->cy;
  }
  coeff_.accel = saved_accel_flag_;
  saved_accel_.clear();
}

// The link passes and the implicit solver add TickInput::push to every body's acceleration,
// static and kinematic bodies included: they are put back after the tick, but inside it a link
// to them would see them move. With links and such bodies, the push is added to the dynamic
// bodies' own accelerations instead (in Real, as the passes add it, so their bits are those of
// an unfolded push) and the tick runs with no push; the arrays are restored after it.
template <class Real>
void detail::WorldKernel<Real>::fold_push(Vec2 push) {
  const std::size_t n = x_.size();
  const Real px = static_cast<Real>(push.x), py = static_cast<Real>(push.y);
  push_saved_.resize(2 * n);
  std::copy(coeff_.accel_x.begin(), coeff_.accel_x.end(), push_saved_.begin());
  std::copy(coeff_.accel_y.begin(), coeff_.accel_y.end(), push_saved_.begin() + n);
  for (std::size_t j = 0; j < n; ++j) {
    if (types_[j] != BodyType::dynamic) continue;
    coeff_.accel_x[j] += px, coeff_.accel_y[j] += py;
  }
  push_saved_flag_ = coeff_.accel;
  coeff_.accel = true;
  if (settings_.integrator != Integrator::implicit_euler) return;
  const auto [cx, cy] = implicit_accelerations();
  push_saved_implicit_.assign(cx, cx + n);
  push_saved_implicit_.insert(push_saved_implicit_.end(), cy, cy + n);
  for (std::size_t j = 0; j < n; ++j) {
    if (types_[j] != BodyType::dynamic) continue;
    cx[j] += double(px), cy[j] += double(py);
  }
}

template <class Real>
void detail::WorldKernel<Real>::unfold_push() {
  const std::size_t n = x_.size();
  std::copy(push_saved_.begin(), push_saved_.begin() + n, coeff_.accel_x.begin());
  std::copy(push_saved_.begin() + n, push_saved_.end(), coeff_.accel_y.begin());
  coeff_.accel = push_saved_flag_;
  if (settings_.integrator != Integrator::implicit_euler) return;
  const auto [cx, cy] = implicit_accelerations();
  std::copy(push_saved_implicit_.begin(), push_saved_implicit_.begin() + n, cx);
  std::copy(push_saved_implicit_.begin() + n, push_saved_implicit_.end(), cy);
}

template <class Real>
void detail::WorldKernel<Real>::apply_input(const TickInput& input) {
  if (sleep_) {
    woken_ = 0, sleeper_contacts_ = 0;
    if (sleepers_ != 0) wake_for_input(input);  // world_sleep.cpp
  }
  if (!input.bodies.empty()) apply_body_inputs(input);
  for (const JointInput& in : input.joints) apply_joint_input(in);  // world_joints.cpp
  if (segments_.moves()) {
    place_segments();  // the carrying bodies' velocities for this tick (world_segments.cpp)
    if (sleep_ && sleepers_ != 0) wake_by_segments();
  }
  if (immovable_dirty_) rebuild_immovable();  // sleepers woken above step from here on
  if (!input.drag_body.is_null() && bodies_.contains(input.drag_body) &&
      types_[bodies_.index(input.drag_body)] == BodyType::dynamic) {
    apply_drag(input);  // world_step.cpp
  }
}

template <class Real>
void detail::WorldKernel<Real>::integrate_with_input(const TickInput& input, bool immovable,
                                                     bool discs) {
  if (contact_.active) save_contact_start();       // world_contacts.cpp
  if (immovable || discs) save_tick_start(discs);  // world_discs.cpp
  const bool forces = !input.bodies.empty() && add_input_forces(input);
  const bool fold = immovable && !net_.a.empty() && (input.push.x != 0.0 || input.push.y != 0.0);
  if (fold) {
    fold_push(input.push);
    integrate(TickInput{.tick = input.tick});  // the push is in the accelerations now
    unfold_push();
  } else {
    integrate(input);  // world_step.cpp
  }
  if (forces) remove_input_forces();
  if (immovable) restore_immovable();
}

}  // namespace fixstep
