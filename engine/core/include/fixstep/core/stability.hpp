// The stability guard: is an integrator's step stable for a body's spring and damping?
//
// Each body's linear part is the test system x'' = -ω² x - γ x' (ω² = k/m, γ = (b + c)/m; for
// a rest-length spring k is the stiffness along the spring, the largest). One integrator step
// maps (x, v) linearly: (x, v)_{n+1} = M (x, v)_n. The step is stable when the spectral radius
// ρ(M) <= 1 (Hairer & Wanner, Solving ODEs II, §IV.2). M is measured by running the real
// integrator, so the guard is exact for every method, damping and substep count.
//
// Bodies joined by links are judged as a network (check_network_stability): the test system
// is then the network's fastest mode, found by power iteration, and the damping flow the
// Strang-split methods apply with damped links (world_coupled.cpp) is part of the step.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/integrators.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/world_settings.hpp"

namespace fixstep {

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

/// The guard's finding for one body.
struct BodyStability {
  Entity body{};          ///< the body: the handle World(def) gives the checked list's body
  double omega = 0.0;     ///< rad/s
  double gamma = 0.0;     ///< 1/s
  double h = 0.0;         ///< step = dt / substeps, s
  double max_step = 0.0;  ///< largest stable step, s (inf: none needed)
  double radius = 0.0;    ///< spectral radius at h
  int min_substeps = 0;   ///< smallest stable substep count for dt; 0 = none
  Stability verdict = Stability::stable;
  /// Empty when stable; otherwise the finding, e.g. "body 'bob' is unstable with rk4 at dt =
  /// 0.1 s and substeps = 1: ω·h = 3.162 exceeds the stability bound 2.785 (...)". States the
  /// fault only: what to change (min_substeps, max_step) is the caller's to word.
  std::string message;
};

/// Checks every dynamic body with a spring or damping at step dt / substeps (dt in s,
/// substeps >= 1) of `integrator`, each on its own (links are ignored here:
/// check_linked_stability judges the bodies links join as a network). Static and kinematic
/// bodies (BodyDef::type) are not integrated and are skipped, whatever their components.
/// Returns one finding per judged body, in order.
[[nodiscard]] std::vector<BodyStability> check_stability(std::span<const BodyDef> bodies,
                                                         Integrator integrator, double dt,
                                                         int substeps);

/// Spectral radius of one step of size h (s) of `integrator` on the mode q'' = -ω² q - γ q'
/// of a network (omega rad/s, gamma 1/s, both >= 0) as World steps it. With damped_links,
/// velocity Verlet and Forest–Ruth apply each link's exact damping flow by colours around the
/// conservative step (link_damping.hpp), which is measured here by stepping two unit masses
/// joined by a link of k = ω²/2, b = γ/2 (their separation obeys the mode's equation).
/// Otherwise, and for every other integrator, the step is the one amplification() measures,
/// and so is the result. The flows are exact, so a pure damping mode is bounded at every h.
[[nodiscard]] double network_amplification(Integrator integrator, double omega, double gamma,
                                           double h, bool damped_links);

/// The guard's finding for a network of bodies joined by links.
struct NetworkStability {
  std::size_t bodies = 0;   ///< bodies in the network
  std::size_t springs = 0;  ///< links in the network
  /// Largest angular frequency, rad/s: sqrt of the top eigenvalue of M^-½ K M^-½ (2n×2n, K the
  /// stiffness at the initial positions), a Rayleigh quotient of power iteration, so a lower
  /// bound; omega_error estimates how far below.
  double omega_max = 0.0;
  /// Estimated relative shortfall, true ω_max / omega_max - 1, from the rise of the Rayleigh
  /// quotient over the second half of the iterations: ~5e-4 at the stop. An estimate, not a
  /// bound: the true shortfall was up to 3 times it on chains (see stability_network.cpp).
  double omega_error = 0.0;
  int iterations = 0;          ///< power iterations used for omega_max
  double gamma = 0.0;          ///< damping rate of the top mode, φᵀ M^-½ C M^-½ φ, 1/s
  double damping_rate = 0.0;   ///< λ_max(M⁻¹C), 1/s (power iteration as for omega_max)
  double h = 0.0;              ///< step = dt / substeps, s
  double max_step = 0.0;       ///< largest stable step for both test modes, s (inf: none needed)
  double radius = 0.0;         ///< largest spectral radius of the two test modes at h
  bool damping_bound = false;  ///< the damping mode (0, damping_rate), not the top mode, binds
  int min_substeps = 0;        ///< smallest stable substep count for dt; 0 = none
  /// The link with the largest k/μ (μ the reduced mass of its ends; the dynamic end's mass when
  /// the other is static or kinematic), index into the links;
  /// nullopt when no link has k > 0.
  std::optional<std::size_t> stiffest_link;
  /// The link with the largest b/μ; nullopt when no link has b > 0.
  std::optional<std::size_t> strongest_damper;
  /// The body of largest displacement |M^-½ φ| in the top mode: the handle World(def) gives it.
  Entity fastest_body{};
  Stability verdict = Stability::stable;
  std::string message;  ///< empty when stable
};

/// The stability guard for bodies joined by links, at the step h = dt / substeps (s) of
/// `integrator`. Two test modes are judged with network_amplification():
///  * the fastest mode (omega_max, gamma): omega_max² is the top eigenvalue of the symmetric
///    M^-½ K M^-½, with M = diag(m) (kg) and K (N/m, 2n×2n) the stiffness of the anchored
///    springs and links, tangent at the initial positions for rest length L > 0:
///    k [(1 - L/ℓ) I + (L/ℓ) d̂d̂ᵀ] at length ℓ, the transverse part clamped at 0 when the
///    spring is compressed (ℓ < L: buckling is the physics, not the integrator) and k I at
///    ℓ = 0; gamma is the Rayleigh quotient of M^-½ C M^-½ on that mode, C (N·s/m) holding the
///    anchored dampers and drag (on the full velocity) and the link dampers (b I, or b d̂d̂ᵀ
///    with L > 0);
///  * the damping mode (0, λ_max(M⁻¹C)), which binds for velocity Verlet and Forest–Ruth with
///    damped links (their flows interleaved with the kicks) and for explicit methods on heavy
///    damping.
/// Static and kinematic bodies (BodyDef::type) are immovable anchors: their 1/m is 0 (their
/// mass is ignored, need not be valid, and their own springs and drag are left out), so a link
/// from a dynamic body of mass m to one acts on m alone, as an anchored spring would (its
/// k/μ, for stiffest_link, is k/m), and a link between two of them does nothing.
/// Both are exact for proportional damping (C = αK + βM: the modes decouple, Géradin & Rixen
/// §2.8) and estimates otherwise. Eigenvalues come from power iteration with the Rayleigh
/// quotient (Golub & Van Loan, Matrix Computations, 4th ed., §8.2.1), stopped when the
/// quotient rose by less than 1e-3 of itself over the second half of the iterations (see
/// stability_network.cpp); O(links + bodies) per iteration, a few hundred iterations on
/// chains of 1000 bodies.
/// Verdict: unstable when a radius exceeds 1, near_limit when h > 0.9 max_step. The message,
/// like check_stability's, names ω_max·h (or λ_max(M⁻¹C)·h) and its bound, the smallest
/// stable substep count, the stiffest link (or strongest damper) with its two bodies, and
/// the fastest body. Throws std::invalid_argument for a link end not among the bodies, both
/// ends on one body, a dynamic body's mass not finite and > 0, dt not finite and > 0, or
/// substeps < 1.
[[nodiscard]] NetworkStability check_network_stability(std::span<const BodyDef> bodies,
                                                       std::span<const LinkDef> links,
                                                       Integrator integrator, double dt,
                                                       int substeps);

/// Which of `body_count` bodies some link joins (links by the handles World(def) gives a
/// definition's bodies). Throws std::invalid_argument for a link whose end is not one of them.
[[nodiscard]] std::vector<bool> linked_bodies(std::size_t body_count,
                                              std::span<const LinkDef> links);

/// check_network_stability for the bodies some link joins (bodies and links as in a WorldDef;
/// fastest_body is the handle World(def) gives it); std::nullopt when there are no links. Throws as
/// check_network_stability and linked_bodies.
[[nodiscard]] std::optional<NetworkStability> check_linked_stability(
    std::span<const BodyDef> bodies, std::span<const LinkDef> links, Integrator integrator,
    double dt, int substeps);

/// The runtime guard's message for `fault` (World::fault()) in a world built from `bodies` and
/// `links` (in creation order) with `settings`, one line:
///   "body[i] \"name\": state left the finite range at tick N (t = T s): vx = inf m/s
///    (allowed |value| <= 1e12). Likely cause: ..."
/// The likely cause comes from the stability guard for that body at settings' dt, integrator
/// and substeps (for a body that a link joins, the network's finding, check_linked_stability):
/// ω·h beyond the integrator's bound (with "stable from substeps = N (dt <= H s)"), explicit
/// Euler on an undamped spring (unstable at every step), or, when the body's step is stable, a
/// force that drives the motion (gravity, a constant force, a push) or extreme starting values;
/// for a kinematic body, its velocity. A contact cap (fault.cap set) is explained as
///   "body[i] \"a\": contacts at tick N (t = T s): max_tick_predictions = 16777216 reached: its
///    impact with body[j] \"b\" (...) was not resolved. Likely cause: ..."
[[nodiscard]] std::string explain_fault(std::span<const BodyDef> bodies,
                                        std::span<const LinkDef> links,
                                        const WorldSettings& settings, const StateFault& fault);

}  // namespace fixstep
