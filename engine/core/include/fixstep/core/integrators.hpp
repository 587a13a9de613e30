// The integrators a scene may choose, and their names.
//
// Every fixstep force is per body and has the form
//   a(x, v) = a_c(x) - γ v,     a_c(x) = -(k/m)(|d| - L) d/|d| + F/m + g + push,  d = x - anchor,
// with γ = (b + c)/m from spring damping b and linear drag c. The system splits into the
// conservative motion A (x' = v, v' = a_c(x)) and the dissipation B (x' = 0, v' = -γ v), whose
// flow is exact: D(τ): v <- v e^{-γτ}. Symplectic methods (velocity Verlet, Forest–Ruth)
// integrate A and compose it with D symmetrically (Strang), so they keep their order on damped
// and dragged systems: a Verlet that simply evaluated -γ v with a stale velocity would drop to
// first order. On a linked world the links' dampers join in as their own exact flows, one link
// at a time, composed by colours as a palindrome around the step (link_damping.hpp), so the
// step stays symmetric and both methods keep their orders on damped networks too.
#pragma once

#include <optional>
#include <string_view>

#include "fixstep/core/types.hpp"

namespace fixstep {

/// Time-stepping schemes for x'' = a(x, v) at a fixed step h (dt / substeps). "Stability bound"
/// is the largest ω·h for which the undamped oscillator x'' = -ω²x stays bounded.
enum class Integrator {
  /// Semi-implicit (symplectic) Euler, velocity first — the game default:
  ///   v_{n+1} = v_n + a(x_n, v_n) h;   x_{n+1} = x_n + v_{n+1} h
  /// Order 1; 1 force evaluation per step; stable for ω·h < 2, where it conserves the modified
  /// energy ½(v² + ω²x² - ω²h x v) exactly. Sources: G. Fiedler, "Integration Basics" (2004);
  /// Hairer, Lubich & Wanner, Geometric Numerical Integration, 2nd ed. (2006), §I.1.2.
  semi_implicit_euler,
  /// Explicit (forward) Euler:
  ///   x_{n+1} = x_n + v_n h;   v_{n+1} = v_n + a(x_n, v_n) h
  /// Order 1; 1 evaluation per step; no stability bound: the undamped oscillator's energy grows
  /// by exactly 1 + (ω·h)² per step (with damping γ it is stable only for ω·h below about
  /// 2ζ). Source: "Integration Basics", section "Explicit Euler".
  explicit_euler,
  /// Velocity Verlet (kick-drift-kick) for a_c, Strang-split with the exact damping flow:
  ///   D(h/2); v += a_c(x) h/2; x += v h; v += a_c(x) h/2; D(h/2)
  /// Order 2 (also with damping and drag); symplectic when γ = 0; 1 new evaluation per step
  /// when the last kick's acceleration is stored for the next step (FSAL) — fixstep instead
  /// re-evaluates a_c(x) in registers (2 per step) on single bodies, which is cheaper than
  /// storing and reloading two arrays per body; on linked worlds it shares the force pass of
  /// the kicks at one position within a tick (1 per step plus 1 per tick), and damped links
  /// add one loop of exact per-link damping flows per step; stable for ω·h < 2. Sources:
  /// Swope, Andersen, Berens & Wilson, J. Chem. Phys. 76, 637 (1982); Strang, SIAM J. Numer.
  /// Anal. 5, 506 (1968) for the splitting.
  velocity_verlet,
  /// Classical fourth-order Runge–Kutta on the full a(x, v):
  ///   k1 = f(y), k2 = f(y + h k1/2), k3 = f(y + h k2/2), k4 = f(y + h k3);
  ///   y += h (k1 + 2k2 + 2k3 + k4)/6,   with y = (x, v) and f(y) = (v, a(x, v)).
  /// Order 4; 4 evaluations per step; not symplectic: on the undamped oscillator energy decays
  /// slowly; stable for ω·h <= 2√2 ≈ 2.83 (|R(iωh)| <= 1 with R(z) = 1 + z + z²/2 + z³/6 +
  /// z⁴/24). Source: Hairer, Nørsett & Wanner, Solving ODEs I, §II.1; Hairer & Wanner, Solving
  /// ODEs II, §IV.2 (stability function).
  rk4,
  /// Implicit (backward) Euler:
  ///   x_{n+1} = x_n + v_{n+1} h;   v_{n+1} = v_n + a(x_{n+1}, v_{n+1}) h
  /// solved per body: in closed form when the forces are linear (rest length 0):
  ///   v_{n+1} = (v_n + h(-(k/m)(x_n - anchor) + F/m + g)) / (1 + hγ + h²k/m),
  /// and by Newton iteration on the 2×2 system otherwise. Order 1; 1 evaluation per step
  /// (several Newton iterations for rest-length springs); unconditionally stable (A-stable), the
  /// oscillator's energy falls every step at any ω·h. Source: Hairer & Wanner, Solving ODEs
  /// II, §IV.3; Baraff & Witkin, "Large steps in cloth simulation", SIGGRAPH 1998.
  implicit_euler,
  /// Forest–Ruth: the fourth-order symplectic composition of three velocity-Verlet steps of
  /// w1·h, w0·h, w1·h with w1 = 1/(2 - 2^{1/3}), w0 = -2^{1/3} w1 (Yoshida's triple jump). Here
  /// each step is the Strang-split damped Verlet step above, which is symmetric, so the
  /// composition stays order 4 with damping and drag. Order 4; 3 new evaluations per step
  /// with shared kicks (FSAL, as linked worlds do within a tick), 6 as fixstep evaluates them
  /// in registers on single bodies; stable for ω·h below about 1.57. Sources: Forest
  /// & Ruth, Physica D 43, 105 (1990); Yoshida, Phys. Lett. A 150, 262 (1990).
  forest_ruth,
};

/// 2^{1/3}, correctly rounded to double, for Forest–Ruth's weights: a literal, so that every
/// compiler and C library gives the same bits (docs/DETERMINISM.md, "Deterministic arithmetic").
inline constexpr double forest_ruth_cbrt2 = 0x1.428a2f98d728bp+0;
/// Forest–Ruth's outer and inner step weights, w1 = 1/(2 - 2^{1/3}) and w0 = -2^{1/3} w1
/// (IEEE division of exact operands: the same bits from every compiler).
inline constexpr double forest_ruth_w1 = 1.0 / (2.0 - forest_ruth_cbrt2);
inline constexpr double forest_ruth_w0 = -forest_ruth_cbrt2 / (2.0 - forest_ruth_cbrt2);

/// Every integrator, in the order they are listed in help texts.
inline constexpr Integrator all_integrators[] = {
    Integrator::semi_implicit_euler, Integrator::explicit_euler,
    Integrator::velocity_verlet,     Integrator::rk4,
    Integrator::implicit_euler,      Integrator::forest_ruth};

/// The scene-file / CLI name of an integrator, e.g. "semi_implicit_euler".
[[nodiscard]] std::string_view integrator_name(Integrator integrator);
/// Parses a scene-file / CLI integrator name; std::nullopt if unknown.
[[nodiscard]] std::optional<Integrator> parse_integrator(std::string_view name);
/// The valid integrator names joined by ", " (for error messages).
[[nodiscard]] std::string_view integrator_names();
/// Theoretical order of accuracy (global error O(h^order)).
[[nodiscard]] int integrator_order(Integrator integrator);
/// Force evaluations a(x, v) per body per step as fixstep performs them: 1 (semi-implicit,
/// explicit and implicit Euler — the latter solved in closed form for linear forces, by
/// Newton's method otherwise), 2 (velocity Verlet), 4 (RK4), 6 (Forest–Ruth). Verlet and
/// Forest–Ruth need only 1 and 3 when the last acceleration is kept (see their entries).
[[nodiscard]] int integrator_evaluations(Integrator integrator);

/// "f32" or "f64".
[[nodiscard]] std::string_view precision_name(Precision precision);
/// Parses "f32" / "f64"; std::nullopt otherwise.
[[nodiscard]] std::optional<Precision> parse_precision(std::string_view name);

}  // namespace fixstep
