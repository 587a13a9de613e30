// The stability guard: is an integrator's step stable for a body's spring and damping?
//
// Each body's linear part is the test system x'' = -ω² x - γ x' (ω² = k/m, γ = (b + c)/m; for
// a rest-length spring k is the stiffness along the spring, the largest). One integrator step
// maps (x, v) linearly: (x, v)_{n+1} = M (x, v)_n. The step is stable when the spectral radius
// ρ(M) <= 1 (Hairer & Wanner, Solving ODEs II, §IV.2). M is measured by running the real
// integrator, so the guard is exact for every method, damping and substep count.
#pragma once

#include <string>
#include <vector>

#include "fixstep/integrators.hpp"

namespace fixstep {

struct Scene;

/// Spectral radius of one step of size h (s) of `integrator` on x'' = -ω² x - γ x', with
/// omega in rad/s and gamma in 1/s (both >= 0). Dimensionless; > 1 means growth per step.
[[nodiscard]] double amplification(Integrator integrator, double omega, double gamma, double h);

/// Largest step h (s) with amplification <= 1 for this ω, γ: +infinity when every step is
/// stable (implicit Euler; no spring and no damping), 0 when none is (explicit Euler on an
/// undamped spring). Found by scanning then bisecting to a relative 1e-12; cached.
[[nodiscard]] double max_stable_step(Integrator integrator, double omega, double gamma);

enum class Stability {
  stable,      ///< h <= 0.9 h_max
  near_limit,  ///< within 10 % of the bound: still stable, warned
  unstable,    ///< ρ > 1: refused unless allow_unstable
};

/// The guard's finding for one body of a scene.
struct BodyStability {
  std::size_t body = 0;     ///< index into Scene::bodies
  double omega = 0.0;       ///< rad/s
  double gamma = 0.0;       ///< 1/s
  double h = 0.0;           ///< step = dt / substeps, s
  double max_step = 0.0;    ///< largest stable step, s (inf: none needed)
  double radius = 0.0;      ///< spectral radius at h
  int min_substeps = 0;     ///< smallest stable substep count for the scene's dt; 0 = none
  Stability verdict = Stability::stable;
  std::string message;      ///< empty when stable
};

/// Checks every body with a spring or damping at the scene's dt, integrator and substeps.
[[nodiscard]] std::vector<BodyStability> check_stability(const Scene& scene);

struct StateFault;

/// The runtime guard's message for `fault` in a simulation built from `scene` (bodies in scene
/// order), one line:
///   "FILE:LINE: body[i] \"name\": state left the finite range at tick N (t = T s): vx = inf
///    m/s (allowed |value| <= 1e12). Likely cause: ..."
/// The likely cause comes from the stability guard for that body at the scene's dt, integrator
/// and substeps: ω·h beyond the integrator's bound (with the substep count that would be
/// stable), explicit Euler on an undamped spring (unstable at every step), or, when the body's
/// step is stable, a force that drives the motion (gravity, a constant force, a push) or
/// extreme starting values.
[[nodiscard]] std::string explain_fault(const Scene& scene, const StateFault& fault);

/// Applies the guard at scene load: throws SceneError (file, the body's line, key "body[i]")
/// for the first unstable body unless the scene sets allow_unstable = true, in which case the
/// error becomes a warning. Returns the warnings (near-limit bodies, allowed instabilities).
std::vector<std::string> enforce_stability(const Scene& scene);

}  // namespace fixstep
