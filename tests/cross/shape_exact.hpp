// The exact checks of bodies with shapes (docs/SHAPES.md, "What is exact and what is bounded"),
// each a small world stepped to a measured outcome and the closed form or bound it must meet.
// One list, run by two harnesses: test_shapes (GoogleTest, natively and under ASan) and
// shape_checks (no GoogleTest: the aarch64 and wasm32 builds run it under their emulators), so
// the checks hold on every platform CI builds, not only by the golden hashes' transitivity.
#pragma once

#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/world_settings.hpp"

namespace fixstep::shape_exact {

/// One measured quantity and the closed interval [low, high] it must lie in (a closed form ±
/// its stated tolerance, or a bound).
struct Measure {
  std::string what;  ///< the quantity and its unit, e.g. "distance slid (m)"
  double value = 0.0;
  double low = 0.0, high = 0.0;
  [[nodiscard]] bool holds() const { return value >= low && value <= high; }
};

/// A check: its name (a GoogleTest-safe identifier) and what its world measures.
struct Check {
  std::string name;
  std::function<std::vector<Measure>()> run;
};

/// GoogleTest's name for a check in its messages (GetParam()).
inline void PrintTo(const Check& c, std::ostream* os) {
  *os << c.name;
}

/// Every exact check: the incline (slides at g (sin θ − μ cos θ), sticks below tan θ = μ), the
/// tipping box (back upright below atan(w/h), over above it), free spin, the elastic gas of
/// boxes and discs, a box resting flat on two corners, a 20-box tower and a 20-row pyramid
/// standing for 10 s, a fast spinning box against a thin wall, and rolling resistance.
[[nodiscard]] std::vector<Check> checks();

/// The checks' world: dt = 1/60 s, contacts with μ and e as every pair's default.
[[nodiscard]] WorldSettings shape_settings(double mu, double e = 0.0);

/// A dynamic box of half-extents hx, hy (m) at `at` turned by `angle` (rad), `mass` kg, under
/// gravity 9.81 m/s² downwards.
[[nodiscard]] BodyDef box_body(double hx, double hy, Vec2 at, double angle = 0.0,
                               double mass = 1.0);

/// `value` within `tolerance` of `expected`.
[[nodiscard]] inline Measure near(std::string what, double value, double expected,
                                  double tolerance) {
  return {std::move(what), value, expected - tolerance, expected + tolerance};
}

}  // namespace fixstep::shape_exact
