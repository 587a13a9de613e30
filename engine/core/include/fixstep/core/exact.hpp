// Exact solutions of the systems fixstep models with linear forces, the truth that tests,
// benchmarks and `fixstep run` measure integrators against.
#pragma once

#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "fixstep/core/components.hpp"

namespace fixstep::exact {

/// Position (m) and velocity (m/s) along one axis.
struct AxisState {
  double x = 0.0;
  double v = 0.0;
};

/// Damping regime of x'' + γ x' + ω² x = f: ζ = γ / (2ω).
enum class Regime {
  none,      ///< ω = 0: no spring (projectile or constant force; γ may be > 0: drag)
  undamped,  ///< γ = 0, ω > 0
  under,     ///< 0 < ζ < 1
  critical,  ///< ζ = 1 (within a relative 1e-9)
  over,      ///< ζ > 1
};

/// Regime of the linear system with ω² = omega2 (1/s², >= 0) and γ = gamma (1/s, >= 0).
/// Informative only: linear() needs no regime switch near ζ = 1 (see there).
/// Throws std::invalid_argument for negative or non-finite omega2 or gamma.
[[nodiscard]] Regime regime(double omega2, double gamma);

/// Exact solution at time t (s) of the scalar linear ODE
///   x'' = -ω² (x - anchor) - γ x' + accel,   x(0) = x0, x'(0) = v0
/// with omega2 = ω² (1/s², >= 0), gamma = γ (1/s, >= 0), anchor (m), accel (m/s², constant).
/// Covers every fixstep body whose forces are linear: spring-dampers with rest length 0
/// (ω² = k/m), damping and drag (γ = (b + c)/m), constant force and gravity
/// (accel = F/m + g). The damped oscillator in all regimes (under-, critically and
/// over-damped), the projectile with and without linear drag and the constant force are
/// special cases. Formulas: Thornton & Marion, Classical Dynamics, 5th ed., §3.5 (damped
/// oscillations); Taylor, Classical Mechanics, §2.2–2.3 (linear air resistance).
/// Numerically stable in every regime (no cancellation near ζ = 1, for tiny γt or huge ω t):
/// the result is continuous across ζ = 1, and with no spring it tends smoothly to
/// x0 + v0 t + accel t²/2 as γ -> 0. With ω² > 0 the motion is computed about the equilibrium
/// anchor + accel/ω², so the absolute error is a few ulps of that equilibrium as well as of
/// the motion: a very weak spring under a strong constant force loses digits (the force is
/// then better modelled with ω² = 0). t may be negative (the same exact flow backwards).
/// Throws std::invalid_argument, naming the parameter, for negative or non-finite
/// omega2/gamma and for non-finite x0, v0, anchor, accel or t.
[[nodiscard]] AxisState linear(double x0, double v0, double omega2, double gamma, double anchor,
                               double accel, double t);

/// Exact state of a body at time t (s) under the components in def, when its forces are linear
/// (no spring, or a spring with rest length 0); std::nullopt otherwise (rest length > 0 makes
/// the force nonlinear). Each axis is linear() with ω² = k/m, γ = (b + c)/m (b only with a
/// spring, c only with drag), anchor = the spring's anchor (0 without one) and
/// accel = F/m + g. The returned Body has def's mass. Throws std::invalid_argument for a mass
/// that is not finite and > 0, a negative or non-finite stiffness, damping, rest length or
/// drag coefficient, and (as linear() does) for a non-finite t or non-finite inputs to an axis.
[[nodiscard]] std::optional<Body> solve(const BodyDef& def, double t);

/// The exact solution of a linear network: bodies whose springs (anchored and links) all have
/// rest length 0 and whose damping is proportional, C = αK + βM (every damper's b = α k of
/// its spring, every body's anchored damping plus drag b + c = α k_anchor + β m; zero damping
/// is the case α = β = 0), under constant forces and gravity. With L = 0 the axes do not
/// interact, so x and y share the n×n matrices K (stiffness, N/m), C (damping, N·s/m) and
/// M = diag(m) (kg), with f = F + m g + k_anchor·anchor (N) per body. Bodies that no link
/// joins never interact: each connected component is solved on its own and may have its own
/// α and β. M x'' = -K x - C x' + f decouples into modes: with K φ = ω² M φ (φᵀMφ = 1), each
/// modal coordinate q = φᵀ M x obeys q'' = -ω² q - (α ω² + β) q' + φᵀ f, solved by linear()
/// (Géradin & Rixen, Mechanical Vibrations, 3rd ed., §2.5 and §2.8, proportional damping).
/// Eigenvalues below 64·n·ε of a component's largest are its rigid motions (ω² = 0: free
/// flight, with drag β). Dense generalized eigen-decomposition (Eigen's
/// GeneralizedSelfAdjointEigenSolver): O(n³) once per component, O(n²) per state(); meant for
/// references up to about a thousand bodies. Accuracy: the eigen-decomposition's round-off,
/// within 1e-13 to 1e-12 of the motion's scale on the tests' networks of one to six bodies.
class LinearNetwork {
 public:
  /// The network of `bodies` and `links` (as in a WorldDef), or std::nullopt when it is
  /// not linear with proportional damping (a rest length > 0, or in some connected component
  /// damping not of the form αK + βM to a relative 1e-9 per damper). Throws
  /// std::invalid_argument for a link end not among the bodies, a link whose ends are the same
  /// body, a negative or non-finite link parameter, or invalid body parameters (as solve(),
  /// and non-finite positions, velocities, anchors, forces or gravity).
  [[nodiscard]] static std::optional<LinearNetwork> make(std::span<const BodyDef> bodies,
                                                         std::span<const LinkDef> links);
  /// Every body's exact position (m) and velocity (m/s) at time t (s), in body order; out
  /// must hold bodies.size() entries (throws std::invalid_argument otherwise or for a
  /// non-finite t). Masses are copied from the definitions.
  void state(double t, std::span<Body> out) const;
  /// Number of bodies (bodies.size() at make()).
  [[nodiscard]] std::size_t size() const;

  LinearNetwork(LinearNetwork&&) noexcept;
  LinearNetwork& operator=(LinearNetwork&&) noexcept;
  ~LinearNetwork();

 private:
  struct Modes;
  explicit LinearNetwork(std::unique_ptr<Modes> modes);
  std::unique_ptr<Modes> modes_;
};

}  // namespace fixstep::exact
