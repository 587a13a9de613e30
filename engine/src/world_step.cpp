// World stepping: force evaluation and the integrators (see integrators.hpp for the formulas,
// orders, stability bounds and sources of each).
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "fixstep/world.hpp"

#if defined(__x86_64__) || defined(__i386__)
#include <xmmintrin.h>
#endif

namespace fixstep {

namespace {

/// Sets flush-to-zero (MXCSR bit 15) and denormals-are-zero (bit 6) for the scope of one step
/// and restores the caller's mode afterwards. x86 only; elsewhere a no-op (ARMv8 has no
/// comparable slow path for subnormals in NEON).
class FlushDenormals {
 public:
  explicit FlushDenormals(bool on) : on_(on) {
#if defined(__x86_64__) || defined(__i386__)
    if (on_) {
      saved_ = _mm_getcsr();
      _mm_setcsr(saved_ | 0x8040u);
    }
#endif
  }
  ~FlushDenormals() {
#if defined(__x86_64__) || defined(__i386__)
    if (on_) _mm_setcsr(saved_);
#endif
  }
  FlushDenormals(const FlushDenormals&) = delete;
  FlushDenormals& operator=(const FlushDenormals&) = delete;

 private:
  bool on_;
  unsigned saved_ = 0;
};

// Yoshida's triple-jump weights (Phys. Lett. A 150, 262 (1990)), as in Forest & Ruth (1990).
const double cbrt2 = std::cbrt(2.0);
const double fr_w1 = 1.0 / (2.0 - cbrt2);
const double fr_w0 = -cbrt2 / (2.0 - cbrt2);

}  // namespace

// Accelerations a(x, v) for every body: forces are summed per term over the bodies that carry
// it (N), scaled by 1/m, then the mass-independent push and gravity are added (m/s²). Each
// term's loop is skipped entirely when it has no bodies. with_damping = false leaves out the
// velocity-dependent terms (spring damping, drag): the conservative part a_c(x).
template <class Real>
template <bool with_damping>
void World<Real>::evaluate(const Real* x, const Real* y, const Real* vx, const Real* vy, Real* ax,
                           Real* ay, const Real push[2]) const {
  const std::size_t n = x_.size();
  std::fill_n(ax, n, Real(0));
  std::fill_n(ay, n, Real(0));
  {  // Hooke + dashpot, rest length 0: F = -k (x - anchor) - b v, per axis.
    const auto& t = linear_springs_;
    for (std::size_t i = 0; i < t.body.size(); ++i) {
      const std::uint32_t j = t.body[i];
      if constexpr (with_damping) {
        ax[j] += -t.k[i] * (x[j] - t.anchor_x[i]) - t.b[i] * vx[j];
        ay[j] += -t.k[i] * (y[j] - t.anchor_y[i]) - t.b[i] * vy[j];
      } else {
        ax[j] += -t.k[i] * (x[j] - t.anchor_x[i]);
        ay[j] += -t.k[i] * (y[j] - t.anchor_y[i]);
      }
    }
  }
  {  // Rest length L > 0: F = -k (|d| - L) d/|d| - b v; no spring force when |d| = 0.
    const auto& t = rest_springs_;
    for (std::size_t i = 0; i < t.body.size(); ++i) {
      const std::uint32_t j = t.body[i];
      const Real dx = x[j] - t.anchor_x[i];
      const Real dy = y[j] - t.anchor_y[i];
      const Real len = std::sqrt(dx * dx + dy * dy);
      const Real s = len > Real(0) ? -t.k[i] * (len - t.rest[i]) / len : Real(0);
      if constexpr (with_damping) {
        ax[j] += s * dx - t.b[i] * vx[j];
        ay[j] += s * dy - t.b[i] * vy[j];
      } else {
        ax[j] += s * dx;
        ay[j] += s * dy;
      }
    }
  }
  for (std::size_t i = 0; i < forces_.body.size(); ++i) {
    ax[forces_.body[i]] += forces_.fx[i];
    ay[forces_.body[i]] += forces_.fy[i];
  }
  if constexpr (with_damping) {
    for (std::size_t i = 0; i < drag_terms_.body.size(); ++i) {  // Stokes drag F = -c v
      const std::uint32_t j = drag_terms_.body[i];
      ax[j] += -drag_terms_.c[i] * vx[j];
      ay[j] += -drag_terms_.c[i] * vy[j];
    }
  }
  const Real* inv_m = inv_mass_.data();
  for (std::size_t j = 0; j < n; ++j) {
    ax[j] *= inv_m[j];
    ay[j] *= inv_m[j];
  }
  if (push[0] != Real(0) || push[1] != Real(0)) {  // user input, m/s²
    for (std::size_t j = 0; j < n; ++j) {
      ax[j] += push[0];
      ay[j] += push[1];
    }
  }
  for (std::size_t i = 0; i < gravity_terms_.body.size(); ++i) {
    ax[gravity_terms_.body[i]] += gravity_terms_.gx[i];
    ay[gravity_terms_.body[i]] += gravity_terms_.gy[i];
  }
}

template <class Real>
void World<Real>::accelerations(std::span<Real> ax, std::span<Real> ay, const TickInput& input) {
  if (ax.size() < body_count() || ay.size() < body_count()) {
    throw std::invalid_argument("World::accelerations: output spans are shorter than body_count()");
  }
  if (terms_dirty_) rebuild_terms();
  const Real push[2] = {static_cast<Real>(input.push.x), static_cast<Real>(input.push.y)};
  evaluate<true>(x_.data(), y_.data(), vx_.data(), vy_.data(), ax.data(), ay.data(), push);
}

template <class Real>
void World<Real>::step(const TickInput& input) {
  const FlushDenormals ftz(settings_.flush_denormals);
  if (terms_dirty_) rebuild_terms();
  if (keep_previous_) {
    std::copy(x_.begin(), x_.end(), prev_x_.begin());
    std::copy(y_.begin(), y_.end(), prev_y_.begin());
  }
  const Real push[2] = {static_cast<Real>(input.push.x), static_cast<Real>(input.push.y)};
  if (push[0] != cached_push_[0] || push[1] != cached_push_[1]) {
    accel_valid_ = false;
    cached_push_[0] = push[0];
    cached_push_[1] = push[1];
  }
  const Real h = static_cast<Real>(settings_.dt / settings_.substeps);
  for (int s = 0; s < settings_.substeps; ++s) substep(h, push);
  ++tick_;
}

template <class Real>
void World<Real>::substep(Real h, const Real push[2]) {
  const std::size_t n = x_.size();
  Real* x = x_.data();
  Real* y = y_.data();
  Real* vx = vx_.data();
  Real* vy = vy_.data();
  const Real* ax = ax_.data();
  const Real* ay = ay_.data();
  switch (settings_.integrator) {
    case Integrator::semi_implicit_euler:
      evaluate<true>(x, y, vx, vy, ax_.data(), ay_.data(), push);
      for (std::size_t j = 0; j < n; ++j) {  // v_{n+1} = v_n + a_n h; x_{n+1} = x_n + v_{n+1} h
        vx[j] += ax[j] * h;
        vy[j] += ay[j] * h;
        x[j] += vx[j] * h;
        y[j] += vy[j] * h;
      }
      accel_valid_ = false;
      break;
    case Integrator::explicit_euler:
      evaluate<true>(x, y, vx, vy, ax_.data(), ay_.data(), push);
      for (std::size_t j = 0; j < n; ++j) {  // x_{n+1} = x_n + v_n h; v_{n+1} = v_n + a_n h
        x[j] += vx[j] * h;
        y[j] += vy[j] * h;
        vx[j] += ax[j] * h;
        vy[j] += ay[j] * h;
      }
      accel_valid_ = false;
      break;
    case Integrator::velocity_verlet:
      strang_verlet(h, push);
      break;
    case Integrator::forest_ruth: {
      const Real h1 = static_cast<Real>(fr_w1 * double(h));
      const Real h0 = static_cast<Real>(fr_w0 * double(h));
      strang_verlet(h1, push);
      strang_verlet(h0, push);
      strang_verlet(h1, push);
      break;
    }
    case Integrator::rk4:
      rk4_step(h, push);
      accel_valid_ = false;
      break;
    case Integrator::implicit_euler:
      implicit_euler_step(h, push);
      accel_valid_ = false;
      break;
  }
}

// S(h) = D(h/2) ∘ VV(h) ∘ D(h/2): Strang splitting of the exact damping flow D around velocity
// Verlet on a_c. Symmetric, so second order, and a valid base for the triple jump.
template <class Real>
void World<Real>::strang_verlet(Real h, const Real push[2]) {
  const bool damped = !coeff_.damped.empty();
  if (damped) damping_flow(0.5 * double(h));
  kick_drift_kick(h, push);
  if (damped) damping_flow(0.5 * double(h));
}

template <class Real>
void World<Real>::kick_drift_kick(Real h, const Real push[2]) {
  const std::size_t n = x_.size();
  Real* x = x_.data();
  Real* y = y_.data();
  Real* vx = vx_.data();
  Real* vy = vy_.data();
  Real* ax = ax_.data();
  Real* ay = ay_.data();
  const Real half = h * Real(0.5);
  if (!accel_valid_) evaluate<false>(x, y, vx, vy, ax, ay, push);
  for (std::size_t j = 0; j < n; ++j) {  // kick h/2, drift h
    vx[j] += ax[j] * half;
    vy[j] += ay[j] * half;
    x[j] += vx[j] * h;
    y[j] += vy[j] * h;
  }
  evaluate<false>(x, y, vx, vy, ax, ay, push);
  for (std::size_t j = 0; j < n; ++j) {  // kick h/2
    vx[j] += ax[j] * half;
    vy[j] += ay[j] * half;
  }
  accel_valid_ = true;  // a_c(x) at the current x: the next kick can reuse it
}

// D(τ): the exact flow of the dissipative part v' = -γ v (x' = 0: the drift x' = v belongs
// to the Verlet part of the splitting), for every damped body.
template <class Real>
void World<Real>::damping_flow(double tau) {
  auto flow = std::find_if(flows_.begin(), flows_.end(),
                           [tau](const DampingFlow& f) { return f.tau == tau; });
  if (flow == flows_.end()) {
    if (flows_.size() >= 4) flows_.clear();  // the step sizes changed
    DampingFlow f;
    f.tau = tau;
    for (std::uint32_t j : coeff_.damped) {
      f.decay.push_back(static_cast<Real>(std::exp(-double(coeff_.gamma[j]) * tau)));
    }
    flows_.push_back(std::move(f));
    flow = flows_.end() - 1;
  }
  for (std::size_t i = 0; i < coeff_.damped.size(); ++i) {
    const std::uint32_t j = coeff_.damped[i];
    vx_[j] *= flow->decay[i];
    vy_[j] *= flow->decay[i];
  }
  // x is unchanged, so a cached a_c(x) stays valid.
}

template <class Real>
void World<Real>::rk4_step(Real h, const Real push[2]) {
  const std::size_t n = x_.size();
  Real *x = x_.data(), *y = y_.data(), *vx = vx_.data(), *vy = vy_.data();
  Real *ax = ax_.data(), *ay = ay_.data();
  Real *sx = sx_.data(), *sy = sy_.data(), *svx = svx_.data(), *svy = svy_.data();
  Real *dx = dx_.data(), *dy = dy_.data(), *dvx = dvx_.data(), *dvy = dvy_.data();
  const Real half = h * Real(0.5);
  evaluate<true>(x, y, vx, vy, ax, ay, push);  // k1 = (v, a(x, v))
  for (std::size_t j = 0; j < n; ++j) {
    dx[j] = vx[j], dy[j] = vy[j], dvx[j] = ax[j], dvy[j] = ay[j];
    sx[j] = x[j] + half * vx[j], sy[j] = y[j] + half * vy[j];
    svx[j] = vx[j] + half * ax[j], svy[j] = vy[j] + half * ay[j];
  }
  evaluate<true>(sx, sy, svx, svy, ax, ay, push);  // k2 at y + h k1 / 2
  for (std::size_t j = 0; j < n; ++j) {
    dx[j] += Real(2) * svx[j], dy[j] += Real(2) * svy[j];
    dvx[j] += Real(2) * ax[j], dvy[j] += Real(2) * ay[j];
    sx[j] = x[j] + half * svx[j], sy[j] = y[j] + half * svy[j];
    svx[j] = vx[j] + half * ax[j], svy[j] = vy[j] + half * ay[j];
  }
  evaluate<true>(sx, sy, svx, svy, ax, ay, push);  // k3 at y + h k2 / 2
  for (std::size_t j = 0; j < n; ++j) {
    dx[j] += Real(2) * svx[j], dy[j] += Real(2) * svy[j];
    dvx[j] += Real(2) * ax[j], dvy[j] += Real(2) * ay[j];
    sx[j] = x[j] + h * svx[j], sy[j] = y[j] + h * svy[j];
    svx[j] = vx[j] + h * ax[j], svy[j] = vy[j] + h * ay[j];
  }
  evaluate<true>(sx, sy, svx, svy, ax, ay, push);  // k4 at y + h k3
  const Real sixth = h / Real(6);
  for (std::size_t j = 0; j < n; ++j) {
    x[j] += sixth * (dx[j] + svx[j]);
    y[j] += sixth * (dy[j] + svy[j]);
    vx[j] += sixth * (dvx[j] + ax[j]);
    vy[j] += sixth * (dvy[j] + ay[j]);
  }
}

// Backward Euler, per body (fixstep's forces never couple bodies). With r = x_{n+1} the
// equations reduce to R(r) = (1 + hγ)(r - x) - h v - h² a_c(r) = 0, v_{n+1} = (r - x)/h.
template <class Real>
void World<Real>::implicit_euler_step(Real h, const Real push[2]) {
  const std::size_t n = x_.size();
  const Coefficients& c = coeff_;
  const Real one(1);
  for (std::size_t j = 0; j < n; ++j) {
    const Real k = c.stiffness[j], g = c.gamma[j];
    const Real cx = c.accel_x[j] + push[0], cy = c.accel_y[j] + push[1];
    if (c.rest[j] == Real(0)) {
      // Linear: a_c(r) = -K (r - anchor) + c, so R is linear in r: solve in closed form.
      const Real denom = one + h * g + h * h * k;
      const Real vxn = (vx_[j] + h * (-k * (x_[j] - c.anchor_x[j]) + cx)) / denom;
      const Real vyn = (vy_[j] + h * (-k * (y_[j] - c.anchor_y[j]) + cy)) / denom;
      vx_[j] = vxn, vy_[j] = vyn;
      x_[j] += h * vxn, y_[j] += h * vyn;
      continue;
    }
    // Rest length L > 0: Newton on R(r) with the Jacobian
    //   J = (1 + hγ) I + h² K [(1 - L/|d|) I + (L/|d|) n nᵀ],  d = r - anchor, n = d/|d|.
    const Real L = c.rest[j];
    Real rx = x_[j] + h * vx_[j], ry = y_[j] + h * vy_[j];
    for (int it = 0; it < 50; ++it) {
      const Real dx = rx - c.anchor_x[j], dy = ry - c.anchor_y[j];
      const Real len = std::sqrt(dx * dx + dy * dy);
      if (!(len > Real(0))) break;
      const Real s = k * (len - L) / len;  // a_c = -s d + c
      const Real res_x = (one + h * g) * (rx - x_[j]) - h * vx_[j] - h * h * (-s * dx + cx);
      const Real res_y = (one + h * g) * (ry - y_[j]) - h * vy_[j] - h * h * (-s * dy + cy);
      const Real nx = dx / len, ny = dy / len;
      const Real t1 = one + h * g + h * h * k * (one - L / len), t2 = h * h * k * L / len;
      const Real j00 = t1 + t2 * nx * nx, j01 = t2 * nx * ny, j11 = t1 + t2 * ny * ny;
      const Real det = j00 * j11 - j01 * j01;
      if (!(std::abs(det) > Real(0))) break;
      const Real step_x = (j11 * res_x - j01 * res_y) / det;
      const Real step_y = (j00 * res_y - j01 * res_x) / det;
      rx -= step_x, ry -= step_y;
      const Real scale = std::abs(rx) + std::abs(ry) + len;
      if (std::abs(step_x) + std::abs(step_y) <= Real(4) * std::numeric_limits<Real>::epsilon() * scale) break;
    }
    vx_[j] = (rx - x_[j]) / h, vy_[j] = (ry - y_[j]) / h;
    x_[j] = rx, y_[j] = ry;
  }
}

// world.hpp declares `extern template class World<Real>`, so every member defined in this
// file is instantiated here explicitly.
#define FIXSTEP_INSTANTIATE(Real)                                                               \
  template void World<Real>::step(const TickInput&);                                            \
  template void World<Real>::accelerations(std::span<Real>, std::span<Real>, const TickInput&); \
  template void World<Real>::evaluate<true>(const Real*, const Real*, const Real*, const Real*, \
                                            Real*, Real*, const Real[2]) const;                 \
  template void World<Real>::evaluate<false>(const Real*, const Real*, const Real*,             \
                                             const Real*, Real*, Real*, const Real[2]) const;   \
  template void World<Real>::substep(Real, const Real[2]);                                      \
  template void World<Real>::strang_verlet(Real, const Real[2]);                                \
  template void World<Real>::kick_drift_kick(Real, const Real[2]);                              \
  template void World<Real>::damping_flow(double);                                              \
  template void World<Real>::rk4_step(Real, const Real[2]);                                     \
  template void World<Real>::implicit_euler_step(Real, const Real[2]);
FIXSTEP_INSTANTIATE(float)
FIXSTEP_INSTANTIATE(double)
#undef FIXSTEP_INSTANTIATE

}  // namespace fixstep
