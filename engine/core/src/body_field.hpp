// The force field of one body and each integrator's step of one body: shared by the fused
// sweep (world_step.cpp, compiled once per SIMD level) and the multi-pass path
// (world_coupled.cpp). Both call the same always-inline functions, so a body's arithmetic is
// the same operations in the same order on either path, and the states are bit-identical
// (tests/core/test_coupled.cpp checks it). Internal to the engine: not installed.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

#include "fixstep/core/integrators.hpp"

namespace fixstep {

// Internal linkage on purpose: the sweeps are compiled for several ISAs from these templates,
// and no wider-ISA copy may be picked by the linker for a baseline caller (see world_step.cpp).
namespace {

enum class SpringShape { none, linear, rest_length };

/// One body's force field a(x, v) = -K s(d) - γ v + c + push (see World::Coefficients),
/// loaded once per sweep. Parts no body declares are compile-time absent: their arrays are
/// never read and their arithmetic never runs. `Decays` damping-flow factors are loaded too
/// (Verlet 1, Forest–Ruth 2).
template <class Real, SpringShape S, bool Damped, bool Accel, int Decays>
struct BodyField {
  static constexpr SpringShape shape = S;
  static constexpr bool damped = Damped;
  static constexpr bool accel = Accel;
  static constexpr int decays = Decays;
  Real k{}, anchor_x{}, anchor_y{}, rest{}, gamma{}, cx{}, cy{};  ///< c includes the push
  Real decay[std::max(Decays, 1)]{};  ///< never empty: C++ has no zero-length arrays

  /// a_c(x): the conservative part (spring, constant force, gravity, push), m/s². The push
  /// is folded into c when the sweep loads it (Accel is on whenever the push is non-zero).
  [[gnu::always_inline]] void conservative(Real x, Real y, Real& ax, Real& ay) const {
    if constexpr (S == SpringShape::none) {
      if constexpr (Accel)
        ax = cx, ay = cy;
      else
        ax = Real(0), ay = Real(0);
    } else {
      Real dx = x - anchor_x, dy = y - anchor_y;
      if constexpr (S == SpringShape::rest_length) {
        // s(d) = (|d| - L) d/|d|; no force at |d| = 0. Both branches are value selects (no
        // division by zero is ever executed), so the sweep stays vectorizable; bodies with
        // L = 0 take factor 1 and get exactly the linear spring's value.
        const Real len = std::sqrt(dx * dx + dy * dy);
        const bool away = len > Real(0);
        const Real stretch = (len - rest) / (away ? len : Real(1));
        const Real f = rest == Real(0) ? Real(1) : (away ? stretch : Real(0));
        dx = f * dx, dy = f * dy;
      }
      ax = -k * dx, ay = -k * dy;
      if constexpr (Accel) ax += cx, ay += cy;
    }
  }
  /// a(x, v) = a_c(x) - γ v, m/s².
  [[gnu::always_inline]] void full(Real x, Real y, Real vx, Real vy, Real& ax, Real& ay) const {
    conservative(x, y, ax, ay);
    if constexpr (Damped) ax -= gamma * vx, ay -= gamma * vy;
  }
};

/// The magnitude below which a damped world's x, y, vx and vy become a zero of their sign every
/// flush_denormals_every ticks (WorldSettings::flush_denormals; world_step.cpp): 2^-55 in f32,
/// 2^-503 in f64, 2^8 times the square root of the least normal number. A value at or above it,
/// its sums (at least 2^-24 of it unless 0) and what 64 ticks of damping leave of it keep their
/// products with a tick's coefficients normal; the dissipation account's squares of smaller
/// velocity components count as 0 (account_square).
template <class Real>
inline constexpr Real flush_below = std::numeric_limits<Real>::digits > 24 ? Real(0x1p-503)
                                                                           : Real(0x1p-55);

/// v, or a zero of v's sign when |v| < below (below = 0: never). A compare and a select, so the
/// sweeps stay vectorized and every SIMD level gives the same bits.
template <class Real>
[[gnu::always_inline]] inline Real flush_tiny(Real v, Real below) {
  return std::abs(v) < below ? std::copysign(Real(0), v) : v;
}

/// |v|² (m²/s²) as the dissipation account squares a velocity: a component below flush_below in
/// magnitude counts as 0, so no square is subnormal (what it leaves out is below 2^-110 m²/s² in
/// f32). A stage velocity can fall that low by cancellation even when the state does not.
template <class Real>
[[gnu::always_inline]] inline Real account_square(Real vx, Real vy) {
  constexpr Real t = flush_below<Real>;
  const Real ux = std::abs(vx) < t ? Real(0) : vx, uy = std::abs(vy) < t ? Real(0) : vy;
  return ux * ux + uy * uy;
}

/// Calls visit(field) with a default BodyField whose compile-time parts match the world's
/// flags: 3 spring shapes x damped or not x constant acceleration or not.
template <class Real, int Decays, class Visit>
void with_field(SpringShape shape, bool damped, bool accel, Visit&& visit) {
  auto pick_accel = [&]<SpringShape S, bool D>() {
    if (accel)
      visit(BodyField<Real, S, D, true, Decays>{});
    else
      visit(BodyField<Real, S, D, false, Decays>{});
  };
  auto pick_damped = [&]<SpringShape S>() {
    if (damped)
      pick_accel.template operator()<S, true>();
    else
      pick_accel.template operator()<S, false>();
  };
  switch (shape) {
    case SpringShape::none:
      pick_damped.template operator()<SpringShape::none>();
      break;
    case SpringShape::linear:
      pick_damped.template operator()<SpringShape::linear>();
      break;
    case SpringShape::rest_length:
      pick_damped.template operator()<SpringShape::rest_length>();
      break;
  }
}

/// Velocity Verlet (kick-drift-kick) on a_c, between two halves of the exact damping flow with
/// factor `decay` = e^{-γh/2}: S(h) = D(h/2) ∘ VV(h) ∘ D(h/2) (Strang). Symmetric, so second
/// order, and a valid base for the triple jump.
/// Track: adds the kinetic energy per unit mass (J/kg) the two damping flows remove to diss.
template <bool Track = false, class Field, class Real>
[[gnu::always_inline]] inline void strang_verlet(Real& x, Real& y, Real& vx, Real& vy,
                                                 const Field& f, Real h, Real decay, Real& diss) {
  const Real half = h * Real(0.5);
  Real ax, ay;
  // The flow D removes ½|v|²(1 - decay²) per unit mass, exactly.
  auto damp = [&] {
    if constexpr (Field::damped) {
      if constexpr (Track) diss += Real(0.5) * account_square(vx, vy);
      vx *= decay, vy *= decay;
      if constexpr (Track) diss -= Real(0.5) * account_square(vx, vy);
    }
  };
  damp();
  f.conservative(x, y, ax, ay);
  vx += ax * half, vy += ay * half;  // kick h/2
  x += vx * h, y += vy * h;          // drift h
  f.conservative(x, y, ax, ay);
  vx += ax * half, vy += ay * half;  // kick h/2
  damp();
}

// Backward Euler for one body (fixstep's forces never couple bodies). With r = x_{n+1} the
// equations reduce to R(r) = (1 + hγ)(r - x) - h v - h² a_c(r) = 0, v_{n+1} = (r - x)/h.
template <class Field, class Real>
[[gnu::always_inline]] inline void implicit_euler(Real& x, Real& y, Real& vx, Real& vy,
                                                  const Field& f, Real h) {
  const Real one(1);
  const Real g = Field::damped ? f.gamma : Real(0);
  const Real cx = Field::accel ? f.cx : Real(0), cy = Field::accel ? f.cy : Real(0);
  if constexpr (Field::shape != SpringShape::rest_length) {
    // Linear: a_c(r) = -K (r - anchor) + c, so R is linear in r: closed form.
    Real denom = one, vxn = vx, vyn = vy;
    if constexpr (Field::damped) denom += h * g;
    if constexpr (Field::shape == SpringShape::linear) {
      denom += h * h * f.k;
      Real ax = -f.k * (x - f.anchor_x), ay = -f.k * (y - f.anchor_y);
      if constexpr (Field::accel) ax += cx, ay += cy;
      vxn += h * ax, vyn += h * ay;
    } else if constexpr (Field::accel) {
      vxn += h * cx, vyn += h * cy;
    }
    vxn /= denom, vyn /= denom;
    vx = vxn, vy = vyn;
    x += h * vxn, y += h * vyn;
  } else {
    // Rest length L > 0 (or a mix with L = 0 bodies): Newton on R(r) with the Jacobian
    //   J = (1 + hγ) I + h² K [(1 - L/|d|) I + (L/|d|) n nᵀ],  d = r - anchor, n = d/|d|.
    const Real k = f.k, L = f.rest;
    Real rx = x + h * vx, ry = y + h * vy;
    for (int it = 0; it < 50; ++it) {
      const Real dx = rx - f.anchor_x, dy = ry - f.anchor_y;
      const Real len = std::sqrt(dx * dx + dy * dy);
      if (!(len > Real(0))) break;
      const Real s = k * (len - L) / len;  // a_c = -s d + c
      const Real res_x = (one + h * g) * (rx - x) - h * vx - h * h * (-s * dx + cx);
      const Real res_y = (one + h * g) * (ry - y) - h * vy - h * h * (-s * dy + cy);
      const Real nx = dx / len, ny = dy / len;
      const Real t1 = one + h * g + h * h * k * (one - L / len), t2 = h * h * k * L / len;
      const Real j00 = t1 + t2 * nx * nx, j01 = t2 * nx * ny, j11 = t1 + t2 * ny * ny;
      const Real det = j00 * j11 - j01 * j01;
      if (!(std::abs(det) > Real(0))) break;
      const Real step_x = (j11 * res_x - j01 * res_y) / det;
      const Real step_y = (j00 * res_y - j01 * res_x) / det;
      rx -= step_x, ry -= step_y;
      const Real scale = std::abs(rx) + std::abs(ry) + len;
      if (std::abs(step_x) + std::abs(step_y) <=
          Real(4) * std::numeric_limits<Real>::epsilon() * scale)
        break;
    }
    vx = (rx - x) / h, vy = (ry - y) / h;
    x = rx, y = ry;
  }
}

/// Per-unit-mass damping power γ|v|² (W/kg) of one body at velocity (vx, vy).
template <class Field, class Real>
[[gnu::always_inline]] inline Real damping_power(const Field& f, Real vx, Real vy) {
  return f.gamma * account_square(vx, vy);
}

/// Step sizes of one integration step, s: h, and Forest–Ruth's w1·h and w0·h.
template <class Real>
struct StepSizes {
  Real h{}, h1{}, h0{};
};

/// Calls step.template operator()<I, Decays>(decay0, decay1) for `method`, with the damping-flow
/// factors it needs: Verlet one array (e^{-γh/2}), Forest–Ruth two (e^{-γ w1 h/2},
/// e^{-γ w0 h/2}), the others none. One switch for the fused sweep and the multi-pass path.
template <class Real, class Step>
void dispatch(Integrator method, const Real* verlet_decay, const Real* fr_decay1,
              const Real* fr_decay0, Step&& step) {
  switch (method) {
    case Integrator::semi_implicit_euler:
      step.template operator()<Integrator::semi_implicit_euler, 0>(nullptr, nullptr);
      break;
    case Integrator::explicit_euler:
      step.template operator()<Integrator::explicit_euler, 0>(nullptr, nullptr);
      break;
    case Integrator::velocity_verlet:
      step.template operator()<Integrator::velocity_verlet, 1>(verlet_decay, nullptr);
      break;
    case Integrator::forest_ruth:
      step.template operator()<Integrator::forest_ruth, 2>(fr_decay1, fr_decay0);
      break;
    case Integrator::rk4:
      step.template operator()<Integrator::rk4, 0>(nullptr, nullptr);
      break;
    case Integrator::implicit_euler:
      step.template operator()<Integrator::implicit_euler, 0>(nullptr, nullptr);
      break;
  }
}

/// One step of integrator I (see integrators.hpp) of one body. Track: adds the energy per unit
/// mass (J/kg) its damping and drag dissipate in the step, integrated as the method integrates
/// (see World::dissipated_energy), to diss; with Track off diss is never touched.
template <Integrator I, bool Track, class Field, class Real>
[[gnu::always_inline]] inline void body_step(Real& x, Real& y, Real& vx, Real& vy, const Field& f,
                                             const StepSizes<Real>& s, Real& diss) {
  constexpr bool count = Track && Field::damped;
  const Real h = s.h;
  if constexpr (I == Integrator::semi_implicit_euler) {
    Real ax, ay;
    f.full(x, y, vx, vy, ax, ay);
    if constexpr (count) diss += h * damping_power(f, vx, vy);
    vx += ax * h, vy += ay * h;  // v_{n+1} = v_n + a_n h
    x += vx * h, y += vy * h;    // x_{n+1} = x_n + v_{n+1} h
  } else if constexpr (I == Integrator::explicit_euler) {
    Real ax, ay;
    f.full(x, y, vx, vy, ax, ay);
    if constexpr (count) diss += h * damping_power(f, vx, vy);
    x += vx * h, y += vy * h;    // x_{n+1} = x_n + v_n h
    vx += ax * h, vy += ay * h;  // v_{n+1} = v_n + a_n h
  } else if constexpr (I == Integrator::velocity_verlet) {
    strang_verlet<Track>(x, y, vx, vy, f, h, f.decay[0], diss);
  } else if constexpr (I == Integrator::forest_ruth) {
    strang_verlet<Track>(x, y, vx, vy, f, s.h1, f.decay[0], diss);
    strang_verlet<Track>(x, y, vx, vy, f, s.h0, f.decay[1], diss);
    strang_verlet<Track>(x, y, vx, vy, f, s.h1, f.decay[0], diss);
  } else if constexpr (I == Integrator::rk4) {
    // y = (x, v), f(y) = (v, a(x, v)); d accumulates k1 + 2 k2 + 2 k3, s is the stage.
    const Real half = h * Real(0.5);
    Real ax, ay, p = Real(0);
    f.full(x, y, vx, vy, ax, ay);  // k1
    if constexpr (count) p = damping_power(f, vx, vy);
    Real dx = vx, dy = vy, dvx = ax, dvy = ay;
    Real sx = x + half * vx, sy = y + half * vy;
    Real svx = vx + half * ax, svy = vy + half * ay;
    f.full(sx, sy, svx, svy, ax, ay);  // k2 at y + h k1 / 2
    if constexpr (count) p += Real(2) * damping_power(f, svx, svy);
    dx += Real(2) * svx, dy += Real(2) * svy;
    dvx += Real(2) * ax, dvy += Real(2) * ay;
    sx = x + half * svx, sy = y + half * svy;
    svx = vx + half * ax, svy = vy + half * ay;
    f.full(sx, sy, svx, svy, ax, ay);  // k3 at y + h k2 / 2
    if constexpr (count) p += Real(2) * damping_power(f, svx, svy);
    dx += Real(2) * svx, dy += Real(2) * svy;
    dvx += Real(2) * ax, dvy += Real(2) * ay;
    sx = x + h * svx, sy = y + h * svy;
    svx = vx + h * ax, svy = vy + h * ay;
    f.full(sx, sy, svx, svy, ax, ay);  // k4 at y + h k3
    if constexpr (count) p += damping_power(f, svx, svy);
    const Real sixth = h / Real(6);
    x += sixth * (dx + svx), y += sixth * (dy + svy);
    vx += sixth * (dvx + ax), vy += sixth * (dvy + ay);
    if constexpr (count) diss += sixth * p;
  } else {
    static_assert(I == Integrator::implicit_euler);
    implicit_euler(x, y, vx, vy, f, h);
    if constexpr (count) diss += h * damping_power(f, vx, vy);
  }
}

}  // namespace

}  // namespace fixstep
