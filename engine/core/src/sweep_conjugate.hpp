// The shape contacts' velocity sweeps as a nonsmooth nonlinear conjugate gradient (NNCG:
// Silcowitz, Niebe and Erleben, "A nonsmooth nonlinear conjugate gradient method for interactive
// contact force problems", The Visual Computer 26, 2010). A projected Gauss–Seidel sweep
// changes every impulse λ by Δλ, the negative of a gradient of the contact problem; after it,
// the impulses go on along the last direction p by β (Fletcher–Reeves: the squared ratio of
// this sweep's change to the last one's), p = β p + Δλ, and the bodies' velocities by the same
// impulses' effect. A stack's slow mode, which plain sweeps shrink by a fraction of a percent
// each, then shrinks by much more: a settled stack's sweeps end (they converge) where plain ones
// never do. β > 1 (the change grew) restarts: p = 0, nothing moved.
//
// The velocities follow the impulses without a pass over the rows: every row's Δλ moved the
// velocities by M⁻¹ Jᵀ Δλ, so the direction of the velocities, M⁻¹ Jᵀ p, follows the same
// recursion from each sweep's change of each body's velocity. This holds while every row that
// moves a velocity in the sweep takes part: the contacts' lanes and units (with rolling
// resistance) do, and a tick in which joints are solved runs the plain sweeps.
#pragma once

#include <cstddef>
#include <vector>

#include "shape_lanes.hpp"

namespace fixstep::detail {

/// For tests: whether the shape contacts' velocity sweeps are accelerated (true, the default)
/// or plain projected Gauss–Seidel sweeps.
void set_sweeps_conjugate(bool on);
[[nodiscard]] bool sweeps_conjugate();

/// The state the conjugate steps carry from sweep to sweep within one tick.
struct SweepConjugate {
  /// What a step does: the first after the tick's first sweep sets the direction to the
  /// sweep's change; a restart clears it; a move goes on along it, then turns it.
  enum class Mode { first, restart, move };
  /// One lane point's two impulses (aligned as the groups are: a Lane alone is aligned to 16
  /// bytes where the build's baseline has no wider vectors, and the AVX clones need 32).
  struct alignas(32) LanePoint {
    shape_lanes::Lane ln, lt;
  };
  /// The lanes' impulses before the sweep and their direction, point by point: the block
  /// groups' two each, then the point groups' one.
  std::vector<LanePoint> before, direction;
  /// The units' rows: ln, lt and the rolling impulse of each row, in units_ order.
  std::vector<double> unit_before, unit_direction;
  /// Each body's velocity before the sweep and its direction, indexed as velocity_.
  std::vector<ShapeMotion> v_before, v_direction;
  /// The last sweep's largest change of a row's own velocity (m/s).
  double last = 0.0;

  SweepConjugate() = default;
  /// Every tick's first sweep makes it again: a copy (a snapshot) holds nothing, and assigning
  /// keeps the target's storage.
  SweepConjugate(const SweepConjugate& /*other*/) {}
  SweepConjugate& operator=(const SweepConjugate& /*other*/) { return *this; }
  SweepConjugate(SweepConjugate&&) noexcept = default;
  SweepConjugate& operator=(SweepConjugate&&) noexcept = default;
  ~SweepConjugate() = default;

  /// One value's step in mode M: its change in the sweep (x − before) is the negative
  /// gradient. The same expressions for a lane of four and a scalar.
  template <Mode M, class T>
  [[gnu::always_inline]] static void step(T& x, T& before, T& p, const T& beta) {
    if constexpr (M == Mode::move) {
      const T d = x - before;
      x += beta * p;
      p = beta * p + d;
    } else if constexpr (M == Mode::first) {
      p = x - before;
    } else {
      p = T{};
    }
    before = x;
  }
};

}  // namespace fixstep::detail
