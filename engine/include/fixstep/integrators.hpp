// The integrators a scene may choose, and their names.
#pragma once

#include <optional>
#include <span>
#include <string_view>

#include "fixstep/types.hpp"

namespace fixstep {

/// Time-stepping schemes for x'' = a(x, v) at a fixed step dt. Each step evaluates the
/// accelerations a_n = a(x_n, v_n) once (one force evaluation per tick).
enum class Integrator {
  /// Semi-implicit (symplectic) Euler, velocity first — the game default:
  ///   v_{n+1} = v_n + a(x_n, v_n) dt
  ///   x_{n+1} = x_n + v_{n+1} dt
  /// First order; symplectic for forces that depend on x only, so energy stays bounded on the
  /// undamped oscillator while ω·dt < 2. Source: G. Fiedler, "Integration Basics" (2004),
  /// section "Semi-implicit Euler"; Hairer, Lubich & Wanner, Geometric Numerical Integration,
  /// 2nd ed., §I.1.2 (symplectic Euler).
  semi_implicit_euler,
  /// Explicit (forward) Euler:
  ///   x_{n+1} = x_n + v_n dt
  ///   v_{n+1} = v_n + a(x_n, v_n) dt
  /// First order; on the undamped oscillator the energy grows by exactly 1 + (ω·dt)^2 per tick,
  /// so it is unstable for every dt. Source: "Integration Basics", section "Explicit Euler".
  explicit_euler,
};

/// Every integrator, in the order they are listed in help texts.
inline constexpr Integrator all_integrators[] = {Integrator::semi_implicit_euler,
                                                 Integrator::explicit_euler};

/// The scene-file / CLI name of an integrator, e.g. "semi_implicit_euler".
[[nodiscard]] std::string_view integrator_name(Integrator integrator);
/// Parses a scene-file / CLI integrator name; std::nullopt if unknown.
[[nodiscard]] std::optional<Integrator> parse_integrator(std::string_view name);
/// The valid integrator names joined by ", " (for error messages).
[[nodiscard]] std::string_view integrator_names();

/// "f32" or "f64".
[[nodiscard]] std::string_view precision_name(Precision precision);
/// Parses "f32" / "f64"; std::nullopt otherwise.
[[nodiscard]] std::optional<Precision> parse_precision(std::string_view name);

}  // namespace fixstep
