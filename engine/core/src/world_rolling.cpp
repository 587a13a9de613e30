// Rolling discs (ContactSettings::rolling): the World's side of angles and angular velocities.
// The contact phases turn the discs (friction at the contact point: world_contacts.cpp for
// planes, disc_events.cpp for impacts between discs, disc_rest.cpp for resting contacts); here
// the moments of inertia are gathered and the angles stepped.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "fixstep/core/step_results.hpp"
#include "world_kernel.hpp"

namespace fixstep {

template <class Real>
void detail::WorldKernel<Real>::rebuild_inertia() {
  std::fill(inv_inertia_.begin(), inv_inertia_.end(), 0.0);
  for (std::size_t i = 0; i < colliders_.data.size(); ++i) {
    const Collider& c = colliders_.data[i];
    const std::size_t j = bodies_.index(colliders_.set.dense[i]);
    if (types_[j] != BodyType::dynamic || c.sensor) continue;
    inv_inertia_[j] = 1.0 / inertia_of(mass_[j], c);
  }
}

template <class Real>
void detail::WorldKernel<Real>::integrate_angles() {
  // θ1 = θ0 + ω1 dt (semi-implicit Euler, ω1 the tick's end angular velocity), in double and
  // wrapped by the exact IEEE remainder, so that the angle keeps its precision however far a
  // disc rolls. A body that does not turn has ω = 0 and keeps its angle.
  // An angular velocity beyond max_state_magnitude (or NaN) is the runtime guard's, as x and v
  // are (World::fault): the angle is then left as it was.
  const double dt = settings_.dt, turn = 2.0 * std::numbers::pi;
  bool out_of_range = false;
  for (std::size_t j = 0; j < angle_.size(); ++j) {
    if (spin_[j] == Real(0)) continue;
    if (!(std::abs(double(spin_[j])) <= max_state_magnitude)) {
      out_of_range = true;
      continue;
    }
    angle_[j] = static_cast<Real>(std::remainder(double(angle_[j]) + double(spin_[j]) * dt, turn));
  }
  if (out_of_range && !fault_) record_fault();
}

}  // namespace fixstep
