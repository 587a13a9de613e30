// The passes of a tick of a linked world (see world_coupled.cpp): link forces, the scatter and
// gather of their sums, the vectorized Euler body pass, and the passes of Euler and RK4 over a
// world's arrays (Passes; velocity Verlet and Forest–Ruth: strang_network.hpp). Internal to the
// engine: not installed.
#pragma once

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "awake_runs.hpp"
#include "body_field.hpp"
#include "world_kernel.hpp"

namespace fixstep {

// Internal linkage, like body_field.hpp: instantiated only in world_coupled.cpp.
namespace {

/// Views of a state (x, y, vx, vy) the link pass reads.
template <class Real>
struct StateView {
  const Real *x, *y, *vx, *vy;
};

/// The force of link l on its end a (end b gets the opposite), N, at state s: with Spring
/// the spring, with Damped the damper (see LinkSpring). With track, adds weight · the link's
/// damping power b|u|² (b(u·d̂)² with rest length), W, to power[l].
template <bool Spring, bool Damped, class Real, class Net>
[[gnu::always_inline]] inline void link_force(const Net& net, StateView<Real> s, std::size_t l,
                                              bool track, Real weight, Real* power, Real& fx,
                                              Real& fy) {
  const std::uint32_t a = net.a[l], b = net.b[l];
  const Real dx = s.x[a] - s.x[b], dy = s.y[a] - s.y[b];
  const Real rest = net.rest[l];
  Real fxl(0), fyl(0), nx(0), ny(0);
  const bool along = rest != Real(0);  // L > 0: spring and damper act along d̂ only
  if (along) {
    const Real len = std::sqrt(dx * dx + dy * dy);
    if (len > Real(0)) nx = dx / len, ny = dy / len;  // else no direction, no force
    if constexpr (Spring) {
      const Real t = len > Real(0) ? net.k[l] * (len - rest) : Real(0);
      fxl = -t * nx, fyl = -t * ny;
    }
  } else if constexpr (Spring) {
    fxl = -net.k[l] * dx, fyl = -net.k[l] * dy;
  }
  if constexpr (Damped) {
    const Real c = net.damping[l];
    const Real ux = s.vx[a] - s.vx[b], uy = s.vy[a] - s.vy[b];
    if (!along) {
      fxl -= c * ux, fyl -= c * uy;
      if (track) power[l] += weight * (c * (ux * ux + uy * uy));
    } else {
      const Real un = ux * nx + uy * ny;
      fxl -= c * un * nx, fyl -= c * un * ny;
      if (track) power[l] += weight * (c * un * un);
    }
  }
  fx = fxl, fy = fyl;
}

/// link_force for links [l0, l1) into fx[l], fy[l].
template <bool Spring, bool Damped, class Real, class Net>
void link_forces(const Net& net, StateView<Real> s, std::size_t l0, std::size_t l1, Real* fx,
                 Real* fy, bool track, Real weight, Real* power) {
  for (std::size_t l = l0; l < l1; ++l) {
    link_force<Spring, Damped>(net, s, l, track, weight, power, fx[l], fy[l]);
  }
}

/// Every link's force added to its ends' sums (acc, N; zeroed by the caller), in link order:
/// for each body the same additions in the same order as the CSR gather, so the same bits;
/// one thread only (two links share a body).
template <bool Spring, bool Damped, class Real, class Net>
void link_scatter(const Net& net, StateView<Real> s, std::size_t l0, std::size_t l1, Real* accx,
                  Real* accy, bool track, Real weight, Real* power) {
  for (std::size_t l = l0; l < l1; ++l) {
    Real fx, fy;
    link_force<Spring, Damped>(net, s, l, track, weight, power, fx, fy);
    const std::uint32_t a = net.a[l], b = net.b[l];
    accx[a] += fx, accy[a] += fy;
    accx[b] -= fx, accy[b] -= fy;
  }
}

/// Body j's link forces summed in link order (the CSR list), N.
template <class Real, class Net>
[[gnu::always_inline]] inline void link_sum(const Net& net, const Real* fx, const Real* fy,
                                            std::size_t j, Real& sx, Real& sy) {
  sx = Real(0), sy = Real(0);
  for (std::uint32_t e = net.offset[j]; e < net.offset[j + 1]; ++e) {
    const std::uint32_t code = net.incident[e];
    const std::uint32_t l = code >> 1;
    if (code & 1u)
      sx -= fx[l], sy -= fy[l];
    else
      sx += fx[l], sy += fy[l];
  }
}

/// Body j's link forces, gathered in link order, times 1/m: m/s².
template <class Real, class Net>
[[gnu::always_inline]] inline void gather(const Net& net, const Real* fx, const Real* fy,
                                          std::size_t j, Real& gx, Real& gy) {
  Real sx, sy;
  link_sum(net, fx, fy, j, sx, sy);
  gx = net.inv_mass[j] * sx, gy = net.inv_mass[j] * sy;
}

template <class Real>
[[gnu::always_inline]] inline bool out_of_range(Real x, Real y, Real vx, Real vy) {
  const Real limit = static_cast<Real>(max_state_magnitude);
  return !(std::abs(x) <= limit && std::abs(y) <= limit && std::abs(vx) <= limit &&
           std::abs(vy) <= limit);
}

/// A body's field, loaded exactly as the fused sweep loads it (world_step.cpp).
template <class Field, class Real, class Coeff>
[[gnu::always_inline]] inline Field load_field(const Coeff& c, std::size_t j, const Real* d0,
                                               const Real* d1, const Real push[2]) {
  Field f;
  if constexpr (Field::shape != SpringShape::none) {
    f.k = c.stiffness[j], f.anchor_x = c.anchor_x[j], f.anchor_y = c.anchor_y[j];
  }
  if constexpr (Field::shape == SpringShape::rest_length) f.rest = c.rest[j];
  if constexpr (Field::damped && Field::decays == 0) f.gamma = c.gamma[j];
  if constexpr (Field::damped && Field::decays >= 1) f.decay[0] = d0[j];
  if constexpr (Field::damped && Field::decays >= 2) f.decay[1] = d1[j];
  if constexpr (Field::accel) f.cx = c.accel_x[j] + push[0], f.cy = c.accel_y[j] + push[1];
  return f;
}

/// The arrays a body pass works on (World's, by pointer, in dense order): the state, the
/// dissipation account and each body's sum of link forces and 1/m. Distinct arrays, so the
/// pointers are restrict: a kernel takes the struct by value, which is how GCC keeps their
/// restrict (restrict locals copied from a reference are ignored, and the loops it then
/// cannot prove independent are not vectorized; -fopt-info-vec-optimized shows it).
template <class Real>
struct BodyArrays {
  Real* __restrict x, * __restrict y, * __restrict vx, * __restrict vy;  ///< m, m/s
  Real* __restrict diss;                           ///< dissipated energy per unit mass, J/kg
  const Real* __restrict accx, * __restrict accy;  ///< the link forces' sums, N
  const Real* __restrict inv_m;                    ///< 1/kg (0 for static and kinematic bodies)
};

/// The bodies' own field (World::Coefficients, by pointer; see BodyField) and the tick's push;
/// restrict and taken by value as BodyArrays.
template <class Real>
struct FieldArrays {
  const Real* __restrict k, * __restrict anchor_x, * __restrict anchor_y;  ///< N/(kg·m), m, m
  const Real* __restrict rest;                                             ///< m
  const Real* __restrict gamma;                                            ///< damping, 1/s
  const Real* __restrict cx, * __restrict cy;  ///< constant acceleration, m/s²
  Real push_x, push_y;                         ///< the tick's push, m/s²
};

/// The body pass of semi-implicit (or, with Explicit, explicit) Euler on a linked world:
/// a = field + (1/m)·acc, then the update, for bodies [j0, j1). A plain loop over restrict
/// pointers (the arrays' copies below) with a branch-free range check (as the fused sweep), so
/// the compiler vectorizes it. Returns true if some new state is out of range.
template <class Field, bool Explicit, bool Track, class Real>
bool euler_bodies(std::size_t j0, std::size_t j1, BodyArrays<Real> b, FieldArrays<Real> c, Real h) {
  Real* __restrict x = b.x, * __restrict y = b.y, * __restrict vx = b.vx, * __restrict vy = b.vy;
  Real* __restrict diss = b.diss;
  const Real* __restrict accx = b.accx, * __restrict accy = b.accy, * __restrict inv_m = b.inv_m;
  const Real* __restrict k = c.k, * __restrict anchor_x = c.anchor_x, * __restrict anchor_y = c.anchor_y, * __restrict rest = c.rest, * __restrict gamma = c.gamma, * __restrict cx = c.cx, * __restrict cy = c.cy;
  const Real push_x = c.push_x, push_y = c.push_y;
  const Real limit = static_cast<Real>(max_state_magnitude);
  Real out = 0;
  for (std::size_t j = j0; j < j1; ++j) {
    Field f;
    if constexpr (Field::shape != SpringShape::none) {
      f.k = k[j], f.anchor_x = anchor_x[j], f.anchor_y = anchor_y[j];
    }
    if constexpr (Field::shape == SpringShape::rest_length) f.rest = rest[j];
    if constexpr (Field::damped) f.gamma = gamma[j];
    if constexpr (Field::accel) f.cx = cx[j] + push_x, f.cy = cy[j] + push_y;
    Real px = x[j], py = y[j], pvx = vx[j], pvy = vy[j], ax, ay;
    f.full(px, py, pvx, pvy, ax, ay);
    if constexpr (Track && Field::damped) diss[j] += h * damping_power(f, pvx, pvy);
    ax += inv_m[j] * accx[j], ay += inv_m[j] * accy[j];
    if constexpr (Explicit) {
      px += pvx * h, py += pvy * h;
      pvx += ax * h, pvy += ay * h;
    } else {
      pvx += ax * h, pvy += ay * h;
      px += pvx * h, py += pvy * h;
    }
    x[j] = px, y[j] = py, vx[j] = pvx, vy[j] = pvy;
    const bool in_range = (int(std::abs(px) <= limit) & int(std::abs(py) <= limit) &
                           int(std::abs(pvx) <= limit) & int(std::abs(pvy) <= limit)) != 0;
    out = in_range ? out : Real(1);
  }
  return out != Real(0);
}

/// The state and scratch one tick of the multi-pass path works on (World's arrays, by
/// pointer), and each integrator's passes. Par is World::parallel, bound to the world.
template <class Real, class Net, class Coeff, class Par>
struct Passes {
  const Net& net;
  const Coeff& c;
  Par par;
  std::size_t n, m;
  Real *x, *y, *vx, *vy, *fx, *fy;
  Real* s[4];  ///< stage state (RK4)
  Real* d[4];  ///< RK4's k1 + 2 k2 + 2 k3; the link sums of Euler and the Strang chain
  Real *power_body, *power_link, *diss_body, *diss_link;
  bool track;
  bool serial;  ///< one thread: link sums by scatter
  const Real* push;
  SpringShape shape;
  bool accel;
  std::atomic<bool>& bad;
  double& work;  ///< J: the external work of static and kinematic link ends (World)
  /// The bodies bodies() visits: the awake runs of a world without links whose sleepers the
  /// free step skips (awake_runs.hpp), or null: every body.
  const std::vector<detail::IndexRun>* runs;

  void flag(bool out) {
    if (out) bad.store(true, std::memory_order_relaxed);
  }
  /// The body arrays with the link sums acc (N).
  [[nodiscard]] BodyArrays<Real> body_arrays(const Real* accx, const Real* accy) const {
    return {x, y, vx, vy, diss_body, accx, accy, net.inv_mass.data()};
  }
  /// The bodies' field arrays with the tick's push.
  [[nodiscard]] FieldArrays<Real> field_arrays() const {
    return {c.stiffness.data(), c.anchor_x.data(), c.anchor_y.data(), c.rest.data(), c.gamma.data(),
            c.accel_x.data(),   c.accel_y.data(),  push[0],           push[1]};
  }
  /// Adds weight (s) times the power, W, the links' static and kinematic ends deliver at state
  /// st to `work`: for each driven link, -F·v of the link's force F on an immovable end moving
  /// at v (F·(v_b - v_a) with F the force on end a and v = 0 for a dynamic end). With Damped,
  /// F holds the damper too. One thread, in link order: the same bits on any thread count.
  template <bool Damped>
  void drive_links(StateView<Real> st, double weight) {
    double power = 0;
    for (const std::uint32_t l : net.driven) {
      Real fx, fy;
      link_force<true, Damped>(net, st, l, false, Real(0), static_cast<Real*>(nullptr), fx, fy);
      const std::uint32_t a = net.a[l], b = net.b[l];
      const bool fixed_a = net.inv_mass[a] == Real(0), fixed_b = net.inv_mass[b] == Real(0);
      const double vx = (fixed_b ? double(st.vx[b]) : 0.0) - (fixed_a ? double(st.vx[a]) : 0.0);
      const double vy = (fixed_b ? double(st.vy[b]) : 0.0) - (fixed_a ? double(st.vy[a]) : 0.0);
      power += double(fx) * vx + double(fy) * vy;
    }
    work += weight * power;
  }
  /// drive_links with the links' dampers when some link is damped.
  void drive(StateView<Real> st, double weight) {
    if (net.driven.empty()) return;
    net.damped ? drive_links<true>(st, weight) : drive_links<false>(st, weight);
  }
  template <bool Spring, bool Damped>
  void links(StateView<Real> st, Real weight) {
    const bool t = track && Damped;
    par(m, [&](std::size_t l0, std::size_t l1) {
      link_forces<Spring, Damped>(net, st, l0, l1, fx, fy, t, weight, power_link);
    });
  }
  void forces(StateView<Real> st, Real weight) {
    if (net.damped)
      links<true, true>(st, weight);
    else
      links<true, false>(st, weight);
  }
  /// The links' integrated power, W·s, into their account, times the method's weight.
  void settle_links(Real scale) {
    if (!track || !net.damped) return;
    for (std::size_t l = 0; l < m; ++l) diss_link[l] += scale * power_link[l], power_link[l] = 0;
  }
  template <int Decays, class Visit>
  void bodies(bool damped, const Real* d0, const Real* d1, Visit&& visit) {
    with_field<Real, Decays>(shape, damped, accel, [&](auto field) {
      using Field = decltype(field);
      auto range = [&](std::size_t j0, std::size_t j1) {
        bool out = false;
        for (std::size_t j = j0; j < j1; ++j) {
          out = visit(load_field<Field>(c, j, d0, d1, push), j) || out;
        }
        flag(out);
      };
      if (runs == nullptr) {
        par(n, range);
        return;
      }
      for (const detail::IndexRun& r : *runs) {  // each body's step is its own: the same bits
        par(r.end - r.begin,
            [&](std::size_t j0, std::size_t j1) { range(r.begin + j0, r.begin + j1); });
      }
    });
  }

  /// Each body's sum of link forces (N) at state st into accx, accy: on one thread a scatter
  /// over the links in link order; on two, a pass over the links and a gather per body in
  /// link order (each body's additions are the same, in the same order: the same bits).
  void accumulate(StateView<Real> st, Real weight, Real* accx, Real* accy) {
    if (serial) {
      std::fill(accx, accx + n, Real(0)), std::fill(accy, accy + n, Real(0));
      const bool t = track && net.damped;
      if (net.damped)
        link_scatter<true, true>(net, st, 0, m, accx, accy, t, weight, power_link);
      else
        link_scatter<true, false>(net, st, 0, m, accx, accy, false, weight, power_link);
      return;
    }
    forces(st, weight);
    par(n, [&](std::size_t j0, std::size_t j1) {
      for (std::size_t j = j0; j < j1; ++j) link_sum(net, fx, fy, j, accx[j], accy[j]);
    });
  }

  /// Semi-implicit (velocity first) or explicit Euler, one step of h: the links' sums, then
  /// one straight pass over the bodies (SoA, restrict, branch-free range check: the compiler
  /// vectorizes it like the fused sweep).
  template <bool Explicit>
  void euler(Real h) {
    Real *accx = d[0], *accy = d[1];
    drive({x, y, vx, vy}, double(h));  // the rectangle at the step's start, as diss_body
    accumulate({x, y, vx, vy}, Real(1), accx, accy);
    const BodyArrays<Real> body = body_arrays(accx, accy);
    const FieldArrays<Real> field = field_arrays();
    with_field<Real, 0>(shape, c.damping, accel, [&](auto f) {
      using Field = decltype(f);
      par(n, [&](std::size_t j0, std::size_t j1) {
        auto run = [&]<bool Track>() {
          return euler_bodies<Field, Explicit, Track>(j0, j1, body, field, h);
        };
        flag(track ? run.template operator()<true>() : run.template operator()<false>());
      });
    });
    settle_links(h);
  }

  /// Classical RK4 (integrators.hpp), one step of h: four link passes and four body passes.
  void rk4(Real h) {
    const Real half = h * Real(0.5), sixth = h / Real(6);
    // Stage i at state st: a = field + links; then `next` writes the next stage.
    auto stage = [&](StateView<Real> st, Real weight, auto next) {
      forces(st, weight);
      drive(st, double(h) / 6.0 * double(weight));  // before `next` overwrites the stage
      bodies<0>(c.damping, nullptr, nullptr, [&](const auto& f, std::size_t j) {
        Real ax, ay, gx, gy;
        const Real SX = st.x[j], SY = st.y[j], SVX = st.vx[j], SVY = st.vy[j];
        f.full(SX, SY, SVX, SVY, ax, ay);
        if constexpr (std::decay_t<decltype(f)>::damped) {
          if (track) power_body[j] += weight * damping_power(f, SVX, SVY);
        }
        gather(net, fx, fy, j, gx, gy);
        ax += gx, ay += gy;
        return next(j, SVX, SVY, ax, ay);
      });
    };
    const StateView<Real> stage_state{s[0], s[1], s[2], s[3]};
    if (track) std::fill(power_body, power_body + n, Real(0));
    stage({x, y, vx, vy}, Real(1), [&](std::size_t j, Real SVX, Real SVY, Real ax, Real ay) {
      d[0][j] = SVX, d[1][j] = SVY, d[2][j] = ax, d[3][j] = ay;  // k1
      s[0][j] = x[j] + half * SVX, s[1][j] = y[j] + half * SVY;
      s[2][j] = vx[j] + half * ax, s[3][j] = vy[j] + half * ay;
      return false;
    });
    for (const Real to : {half, h}) {  // k2 (next stage at y + h k2/2), k3 (at y + h k3)
      stage(stage_state, Real(2), [&](std::size_t j, Real SVX, Real SVY, Real ax, Real ay) {
        d[0][j] += Real(2) * SVX, d[1][j] += Real(2) * SVY;
        d[2][j] += Real(2) * ax, d[3][j] += Real(2) * ay;
        s[0][j] = x[j] + to * SVX, s[1][j] = y[j] + to * SVY;
        s[2][j] = vx[j] + to * ax, s[3][j] = vy[j] + to * ay;
        return false;
      });
    }
    stage(stage_state, Real(1), [&](std::size_t j, Real SVX, Real SVY, Real ax, Real ay) {
      const Real X = x[j] + sixth * (d[0][j] + SVX), Y = y[j] + sixth * (d[1][j] + SVY);
      const Real VX = vx[j] + sixth * (d[2][j] + ax), VY = vy[j] + sixth * (d[3][j] + ay);
      x[j] = X, y[j] = Y, vx[j] = VX, vy[j] = VY;
      if (track) diss_body[j] += sixth * power_body[j];
      return out_of_range(X, Y, VX, VY);
    });
    settle_links(sixth);
  }
};

}  // namespace

}  // namespace fixstep
