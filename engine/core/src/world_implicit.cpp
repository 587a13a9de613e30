// Implicit (backward) Euler for a world with links: the whole network's equations solved each
// step with Eigen's sparse solvers.
//
// With r = x_{n+1} and v_{n+1} = (r - x)/h the step is G(r) = M (r - x - h v) - h² F(r, (r-x)/h)
// = 0 (Hairer & Wanner, Solving ODEs II, §IV.3; Baraff & Witkin, "Large steps in cloth
// simulation", SIGGRAPH 1998). Its Jacobian is J = M + h C + h² K with K = -∂F/∂x the tangent
// stiffness and C = -∂F/∂v the damping matrix.
//  * Linear forces (every spring with rest length 0): F is affine, K and C are constant and
//    equal for both axes, and G is solved exactly in velocities,
//      (M + h C + h² K) v_{n+1} = M v_n + h F(x_n, 0),
//    with one LDLᵀ factorisation per step size reused every tick (n×n, symmetric positive
//    definite), two right-hand sides (x and y).
//  * Rest-length springs: Newton's method on G over both axes (2n unknowns), each spring's
//    tangent stiffness k[(1 - L/ℓ) I + (L/ℓ) n̂n̂ᵀ] and damper b n̂n̂ᵀ (the dependence of n̂ in
//    the damper on r is left out of J: the iteration still converges to G = 0, a little more
//    slowly); a sparse LU per iteration, since J can be indefinite under compression.
// The solve runs in double for f32 worlds too; the state is rounded to the world's precision.
#include <fmt/format.h>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <cmath>
#include <limits>
#include <new>

#include "body_field.hpp"
#include "fixstep/core/components.hpp"
#include "fixstep/core/limits.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/stop_request.hpp"
#include "world_kernel.hpp"

namespace fixstep {

namespace detail {

template <class Real>
class ImplicitSolver {
 public:
  /// The network in double, SI units (filled by World::step_implicit_network).
  struct Spring {
    std::uint32_t a = 0, b = 0;  ///< bodies (b unused for anchored springs)
    double k = 0, damping = 0, rest = 0, anchor_x = 0, anchor_y = 0;  ///< damping: links only
    bool anchored = false;
    std::size_t link = 0;  ///< dense link index (links only)
  };
  std::vector<double> mass, drag, cx, cy;  ///< kg; b + c of per-body dampers, N·s/m; m/s²
  std::vector<Spring> springs;
  bool linear = true;
  /// A new state's value below this magnitude is written back as a zero of its sign (the
  /// world's flush_below, body_field.hpp; 0: none): solved in double, a velocity (r - x)/h can
  /// be far below the least normal Real while r and x are not.
  double flush = 0;

  /// One step of h (s). Returns true if the new state is out of range.
  bool step(Real* x, Real* y, Real* vx, Real* vy, double h, const Real push[2], bool track,
            Real* diss_body, Real* diss_link);

 private:
  using Sparse = Eigen::SparseMatrix<double>;
  /// v in the world's precision, flushed below `flush`.
  [[nodiscard]] Real narrow(double v) const { return static_cast<Real>(flush_tiny(v, flush)); }
  void build_linear(double h);
  bool step_linear(Real* x, Real* y, Real* vx, Real* vy, double h, const Real push[2]);
  bool step_newton(Real* x, Real* y, Real* vx, Real* vy, double h, const Real push[2]);
  // The phases of step_newton, in the order they run.
  void start_newton(const Real* x, const Real* y, const Real* vx, const Real* vy, double h);
  void newton_bodies(const Real* x, const Real* y, const Real* vx, const Real* vy, double h,
                     const Real push[2]);
  void newton_springs(const Real* x, const Real* y, double h);
  bool newton_update();
  bool finish_newton(Real* x, Real* y, Real* vx, Real* vy, double h) const;
  /// One spring's force on its end a (N) and its block of the Jacobian, h²K + hC (kg).
  struct SpringJacobian {
    double fx, fy, j00, j01, j11;
  };
  SpringJacobian spring_jacobian(const Spring& s, const Real* x, const Real* y, double h) const;
  void add_block(Eigen::Index p, Eigen::Index q, double sign, double b00, double b01, double b11);
  void account(const Real* x, const Real* y, const Real* vx, const Real* vy, double h,
               Real* diss_body, Real* diss_link);

  double factor_h_ = -1.0;
  Eigen::SimplicialLDLT<Sparse> ldlt_;
  Eigen::SparseLU<Sparse> lu_;
  bool lu_analyzed_ = false;
  std::vector<Eigen::Triplet<double>> triplets_;
  Sparse jacobian_;
  Eigen::VectorXd rhs_x_, rhs_y_, sol_x_, sol_y_, r_, g_, delta_;
};

template <class Real>
void ImplicitSolverDeleter<Real>::operator()(ImplicitSolver<Real>* s) const {
  delete s;
}

template <class Real>
void ImplicitSolver<Real>::build_linear(double h) {
  const std::size_t n = mass.size();
  triplets_.clear();
  for (std::size_t j = 0; j < n; ++j) {
    triplets_.emplace_back(j, j, mass[j] + h * drag[j]);
  }
  for (const Spring& s : springs) {
    const double kk = h * h * s.k, cc = h * s.damping;
    triplets_.emplace_back(s.a, s.a, kk + cc);
    if (s.anchored) continue;
    triplets_.emplace_back(s.b, s.b, kk + cc);
    triplets_.emplace_back(s.a, s.b, -(kk + cc));
    triplets_.emplace_back(s.b, s.a, -(kk + cc));
  }
  Sparse a(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
  a.setFromTriplets(triplets_.begin(), triplets_.end());
  throw_if_stop_requested();  // the factorisation is the longest step of a linear network
  ldlt_.compute(a);
  factor_h_ = h;
  rhs_x_.resize(n), rhs_y_.resize(n), sol_x_.resize(n), sol_y_.resize(n);
}

template <class Real>
bool ImplicitSolver<Real>::step_linear(Real* x, Real* y, Real* vx, Real* vy, double h,
                                       const Real push[2]) {
  if (h != factor_h_) build_linear(h);
  // Eigen's vectors are indexed by Eigen::Index (signed).
  const auto n = static_cast<Eigen::Index>(mass.size());
  // rhs = M v + h F(x, 0): the forces at the old positions with zero velocity.
  for (Eigen::Index j = 0; j < n; ++j) {
    const double ax = cx[j] + double(push[0]), ay = cy[j] + double(push[1]);
    rhs_x_[j] = mass[j] * (double(vx[j]) + h * ax);
    rhs_y_[j] = mass[j] * (double(vy[j]) + h * ay);
  }
  for (const Spring& s : springs) {
    const double bx = s.anchored ? s.anchor_x : double(x[s.b]);
    const double by = s.anchored ? s.anchor_y : double(y[s.b]);
    const double fx = -s.k * (double(x[s.a]) - bx), fy = -s.k * (double(y[s.a]) - by);
    rhs_x_[s.a] += h * fx, rhs_y_[s.a] += h * fy;
    if (!s.anchored) rhs_x_[s.b] -= h * fx, rhs_y_[s.b] -= h * fy;
  }
  sol_x_ = ldlt_.solve(rhs_x_);
  sol_y_ = ldlt_.solve(rhs_y_);
  const Real hr = static_cast<Real>(h);
  bool out = false;
  const double limit = max_state_magnitude;
  for (Eigen::Index j = 0; j < n; ++j) {
    vx[j] = narrow(sol_x_[j]), vy[j] = narrow(sol_y_[j]);
    x[j] += hr * vx[j], y[j] += hr * vy[j];
    out = out || !(std::abs(double(x[j])) <= limit && std::abs(double(y[j])) <= limit &&
                   std::abs(double(vx[j])) <= limit && std::abs(double(vy[j])) <= limit);
  }
  return out;
}

template <class Real>
bool ImplicitSolver<Real>::step_newton(Real* x, Real* y, Real* vx, Real* vy, double h,
                                       const Real push[2]) {
  start_newton(x, y, vx, vy, h);
  for (int it = 0; it < 50; ++it) {
    throw_if_stop_requested();  // per Newton iteration: one sparse LU each
    triplets_.clear();
    // G = M (r - x - h v) - h² F(r, (r - x)/h),  J = M + h C + h² K.
    newton_bodies(x, y, vx, vy, h, push);
    newton_springs(x, y, h);
    if (!newton_update()) break;
  }
  return finish_newton(x, y, vx, vy, h);
}

/// Newton's first iterate: an explicit drift, r = x + h v.
template <class Real>
void ImplicitSolver<Real>::start_newton(const Real* x, const Real* y, const Real* vx,
                                        const Real* vy, double h) {
  // Eigen's vectors are indexed by Eigen::Index (signed).
  const auto n = static_cast<Eigen::Index>(mass.size());
  const Eigen::Index N = 2 * n;
  r_.resize(N), g_.resize(N), delta_.resize(N);
  for (Eigen::Index j = 0; j < n; ++j) {
    r_[2 * j] = double(x[j]) + h * double(vx[j]);
    r_[2 * j + 1] = double(y[j]) + h * double(vy[j]);
  }
}

/// The 2×2 block B (symmetric: b00, b01, b11) times sign at the rows of body p and the columns
/// of body q of the Jacobian.
template <class Real>
void ImplicitSolver<Real>::add_block(Eigen::Index p, Eigen::Index q, double sign, double b00,
                                     double b01, double b11) {
  auto add = [&](Eigen::Index i, Eigen::Index k, double v) {
    triplets_.emplace_back(static_cast<int>(i), static_cast<int>(k), v);
  };
  add(2 * p, 2 * q, sign * b00), add(2 * p, 2 * q + 1, sign * b01);
  add(2 * p + 1, 2 * q, sign * b01), add(2 * p + 1, 2 * q + 1, sign * b11);
}

/// Each body's part of G at the iterate (its inertia, drag, constant forces and the push) and
/// its diagonal block M + h·drag of J.
template <class Real>
void ImplicitSolver<Real>::newton_bodies(const Real* x, const Real* y, const Real* vx,
                                         const Real* vy, double h, const Real push[2]) {
  const auto n = static_cast<Eigen::Index>(mass.size());
  for (Eigen::Index j = 0; j < n; ++j) {
    const double ux = (r_[2 * j] - double(x[j])) / h, uy = (r_[2 * j + 1] - double(y[j])) / h;
    const double fx = mass[j] * (cx[j] + double(push[0])) - drag[j] * ux;
    const double fy = mass[j] * (cy[j] + double(push[1])) - drag[j] * uy;
    g_[2 * j] = mass[j] * (r_[2 * j] - double(x[j]) - h * double(vx[j])) - h * h * fx;
    g_[2 * j + 1] = mass[j] * (r_[2 * j + 1] - double(y[j]) - h * double(vy[j])) - h * h * fy;
    add_block(j, j, 1.0, mass[j] + h * drag[j], 0.0, mass[j] + h * drag[j]);
  }
}

template <class Real>
typename ImplicitSolver<Real>::SpringJacobian ImplicitSolver<Real>::spring_jacobian(
    const Spring& s, const Real* x, const Real* y, double h) const {
  const Eigen::Index a = s.a, b = s.b;
  const double rbx = s.anchored ? s.anchor_x : r_[2 * b];
  const double rby = s.anchored ? s.anchor_y : r_[2 * b + 1];
  const double dx = r_[2 * a] - rbx, dy = r_[2 * a + 1] - rby;
  const double ubx = s.anchored ? 0.0 : (r_[2 * b] - double(x[b])) / h;
  const double uby = s.anchored ? 0.0 : (r_[2 * b + 1] - double(y[b])) / h;
  const double ux = (r_[2 * a] - double(x[a])) / h - ubx;
  const double uy = (r_[2 * a + 1] - double(y[a])) / h - uby;
  double fx, fy, k00, k01, k11, c00, c01, c11;
  const double len = std::sqrt(dx * dx + dy * dy);
  if (s.rest == 0.0 || !(len > 0.0)) {
    fx = -s.k * dx - s.damping * ux, fy = -s.k * dy - s.damping * uy;
    k00 = k11 = s.k, k01 = 0.0;
    c00 = c11 = s.damping, c01 = 0.0;
    if (s.rest != 0.0) fx = fy = 0.0, k00 = k11 = c00 = c11 = 0.0;  // no direction
  } else {
    const double nx = dx / len, ny = dy / len, q = s.rest / len;
    const double un = ux * nx + uy * ny;
    fx = -s.k * (len - s.rest) * nx - s.damping * un * nx;
    fy = -s.k * (len - s.rest) * ny - s.damping * un * ny;
    k00 = s.k * ((1.0 - q) + q * nx * nx), k01 = s.k * q * nx * ny;
    k11 = s.k * ((1.0 - q) + q * ny * ny);
    c00 = s.damping * nx * nx, c01 = s.damping * nx * ny, c11 = s.damping * ny * ny;
  }
  return {fx, fy, h * h * k00 + h * c00, h * h * k01 + h * c01, h * h * k11 + h * c11};
}

/// Each spring's force in G and its blocks of J ([B -B; -B B] on its two bodies, B alone on an
/// anchored spring's body).
template <class Real>
void ImplicitSolver<Real>::newton_springs(const Real* x, const Real* y, double h) {
  for (const Spring& s : springs) {
    const Eigen::Index a = s.a, b = s.b;
    const SpringJacobian t = spring_jacobian(s, x, y, h);
    g_[2 * a] -= h * h * t.fx, g_[2 * a + 1] -= h * h * t.fy;
    add_block(a, a, 1.0, t.j00, t.j01, t.j11);
    if (s.anchored) continue;
    g_[2 * b] += h * h * t.fx, g_[2 * b + 1] += h * h * t.fy;
    add_block(b, b, 1.0, t.j00, t.j01, t.j11);
    add_block(a, b, -1.0, t.j00, t.j01, t.j11);
    add_block(b, a, -1.0, t.j00, t.j01, t.j11);
  }
}

/// Solves J δ = G (a sparse LU) and steps r -= δ. False when the iteration is over: the
/// factorisation failed or δ is within a few ulps of r.
template <class Real>
bool ImplicitSolver<Real>::newton_update() {
  const Eigen::Index N = r_.size();
  jacobian_.resize(N, N);
  jacobian_.setFromTriplets(triplets_.begin(), triplets_.end());
  if (!lu_analyzed_) lu_.analyzePattern(jacobian_), lu_analyzed_ = true;
  throw_if_stop_requested();  // again after the analysis, before the factorisation
  lu_.factorize(jacobian_);
  if (lu_.info() != Eigen::Success) return false;
  delta_ = lu_.solve(g_);
  r_ -= delta_;
  const double scale = r_.cwiseAbs().maxCoeff() + 1.0;
  return delta_.cwiseAbs().maxCoeff() > 4.0 * std::numeric_limits<double>::epsilon() * scale;
}

/// The state at the last iterate, v = (r - x)/h; true if it is out of range.
template <class Real>
bool ImplicitSolver<Real>::finish_newton(Real* x, Real* y, Real* vx, Real* vy, double h) const {
  const auto n = static_cast<Eigen::Index>(mass.size());
  bool out = false;
  const double limit = max_state_magnitude;
  for (Eigen::Index j = 0; j < n; ++j) {
    const double nvx = (r_[2 * j] - double(x[j])) / h, nvy = (r_[2 * j + 1] - double(y[j])) / h;
    x[j] = narrow(r_[2 * j]), y[j] = narrow(r_[2 * j + 1]);
    vx[j] = narrow(nvx), vy[j] = narrow(nvy);
    out = out || !(std::abs(r_[2 * j]) <= limit && std::abs(r_[2 * j + 1]) <= limit &&
                   std::abs(nvx) <= limit && std::abs(nvy) <= limit);
  }
  return out;
}

template <class Real>
void ImplicitSolver<Real>::account(const Real* x, const Real* y, const Real* vx, const Real* vy,
                                   double h, Real* diss_body, Real* diss_link) {
  // Backward Euler's rectangle: h · the damping power at the end of the step. Anchored
  // dampers act on the full velocity and are in drag[] (per unit mass: J/kg).
  for (std::size_t j = 0; j < mass.size(); ++j) {
    const double v2 = double(vx[j]) * double(vx[j]) + double(vy[j]) * double(vy[j]);
    diss_body[j] += static_cast<Real>(h * drag[j] * v2 / mass[j]);
  }
  for (const Spring& s : springs) {
    if (s.anchored || s.damping == 0.0) continue;
    const double ux = double(vx[s.a]) - double(vx[s.b]), uy = double(vy[s.a]) - double(vy[s.b]);
    double p = ux * ux + uy * uy;
    if (s.rest != 0.0) {
      const double dx = double(x[s.a]) - double(x[s.b]), dy = double(y[s.a]) - double(y[s.b]);
      const double len = std::sqrt(dx * dx + dy * dy);
      const double un = len > 0.0 ? (ux * dx + uy * dy) / len : 0.0;
      p = un * un;
    }
    diss_link[s.link] += static_cast<Real>(h * s.damping * p);
  }
}

template <class Real>
bool ImplicitSolver<Real>::step(Real* x, Real* y, Real* vx, Real* vy, double h, const Real push[2],
                                bool track, Real* diss_body, Real* diss_link) {
  const bool out = linear ? step_linear(x, y, vx, vy, h, push) : step_newton(x, y, vx, vy, h, push);
  if (track) account(x, y, vx, vy, h, diss_body, diss_link);
  return out;
}

}  // namespace detail

template <class Real>
detail::ImplicitSolver<Real>& detail::WorldKernel<Real>::implicit_solver() {
  if (!implicit_) {
    // The network in double from the authoritative components (rebuilt after any change).
    implicit_.reset(new detail::ImplicitSolver<Real>());
    detail::ImplicitSolver<Real>& s = *implicit_;
    const std::size_t n = body_count();
    s.mass = mass_;
    s.flush = settings_.flush_denormals ? double(flush_below<Real>) : 0.0;
    s.drag.assign(n, 0.0), s.cx.assign(n, 0.0), s.cy.assign(n, 0.0);
    s.linear = true;
    for (std::size_t i = 0; i < springs_.data.size(); ++i) {
      const SpringDamper& sd = springs_.data[i];
      const std::size_t j = bodies_.index(springs_.set.dense[i]);
      if (types_[j] != BodyType::dynamic) continue;
      s.drag[j] += sd.damping;
      s.springs.push_back({.a = static_cast<std::uint32_t>(j),
                           .b = 0,
                           .k = sd.stiffness,
                           .damping = 0.0,
                           .rest = sd.rest_length,
                           .anchor_x = sd.anchor.x,
                           .anchor_y = sd.anchor.y,
                           .anchored = true,
                           .link = 0});
      s.linear = s.linear && sd.rest_length == 0.0;
    }
    for (std::size_t i = 0; i < drags_.data.size(); ++i) {
      s.drag[bodies_.index(drags_.set.dense[i])] += drags_.data[i].coefficient;
    }
    for (std::size_t i = 0; i < constant_forces_.data.size(); ++i) {
      const std::size_t j = bodies_.index(constant_forces_.set.dense[i]);
      s.cx[j] += constant_forces_.data[i].force.x / mass_[j];
      s.cy[j] += constant_forces_.data[i].force.y / mass_[j];
    }
    for (std::size_t i = 0; i < gravities_.data.size(); ++i) {
      const std::size_t j = bodies_.index(gravities_.set.dense[i]);
      s.cx[j] += gravities_.data[i].acceleration.x, s.cy[j] += gravities_.data[i].acceleration.y;
    }
    // Static and kinematic bodies: no forces of their own, and a mass so large (10^30 kg) that
    // links move them by nothing a double resolves; after the tick they are put where their
    // velocity takes them (restore_immovable).
    for (std::size_t j = 0; j < n; ++j) {
      if (types_[j] == BodyType::dynamic) continue;
      s.mass[j] = 1e30, s.drag[j] = 0.0, s.cx[j] = 0.0, s.cy[j] = 0.0;
    }
    for (std::size_t l = 0; l < link_defs_.size(); ++l) {
      const LinkSpring& ls = link_defs_[l].spring;
      s.springs.push_back({.a = net_.a[l],
                           .b = net_.b[l],
                           .k = ls.stiffness,
                           .damping = ls.damping,
                           .rest = ls.rest_length,
                           .anchor_x = 0.0,
                           .anchor_y = 0.0,
                           .anchored = false,
                           .link = l});
      s.linear = s.linear && ls.rest_length == 0.0;
    }
  }
  return *implicit_;
}

template <class Real>
std::pair<double*, double*> detail::WorldKernel<Real>::implicit_accelerations() {
  detail::ImplicitSolver<Real>& s = implicit_solver();
  return {s.cx.data(), s.cy.data()};
}

template <class Real>
bool detail::WorldKernel<Real>::step_implicit_network(Real h, const Real push[2]) {
  try {
    return implicit_solver().step(x_.data(), y_.data(), vx_.data(), vy_.data(), double(h), push,
                                  settings_.track_dissipation, dissipated_body_.data(),
                                  dissipated_link_.data());
  } catch (const std::bad_alloc&) {  // the factorisation's memory (limits.hpp estimates it)
    implicit_.reset();               // what it did get, back
    throw LimitError(fmt::format(
        "implicit_euler on {} bodies: out of memory in its sparse factorisation: use "
        "semi_implicit_euler with substeps (stable where the stability guard says) for a "
        "network this large",
        body_count()));
  }
}

template struct detail::ImplicitSolverDeleter<float>;
template struct detail::ImplicitSolverDeleter<double>;

}  // namespace fixstep
