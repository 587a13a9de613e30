// The integrator's κ: how far a contact impulse moves a body within the tick it acts in.
#pragma once

#include "fixstep/core/integrators.hpp"

namespace fixstep::detail {

/// How far an integrator moves a body under a constant force, per unit of the velocity that
/// force gives it over one tick, in units of dt: x1 - x0 = κ dt Δv. With n substeps of h =
/// dt/n, semi-implicit (and implicit) Euler move F/m h² n(n+1)/2 = F/m dt² (n+1)/2n, explicit
/// Euler (n-1)/2n, and the methods exact for constant forces ½.
inline double contact_kappa(Integrator integrator, int substeps) {
  const double n = substeps;
  switch (integrator) {
    case Integrator::semi_implicit_euler:
    case Integrator::implicit_euler:
      return (n + 1.0) / (2.0 * n);
    case Integrator::explicit_euler:
      return (n - 1.0) / (2.0 * n);
    default:
      return 0.5;
  }
}

}  // namespace fixstep::detail
