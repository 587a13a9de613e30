// The steppers bench_coupled times and measures: fixstep's World (semi-implicit Euler) and
// the hand-written edge-list loop, behind the Peer interface; the peer engines are in
// peers_chipmunk.cpp and peers_box2d.cpp. Built at -O3 like the engine's multi-pass path.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "coupled.hpp"
#include "fixstep/core/components.hpp"
#include "fixstep/core/world.hpp"
#include "flush_denormals.hpp"
#include "world_kernel.hpp"

#if defined(__x86_64__) || defined(__i386__)
#include <xmmintrin.h>
#endif

namespace coupled {

using fixstep::Body;
using fixstep::BodyDef;
using BodyLink = fixstep::IndexLink;
using fixstep::SpringDamper;
using fixstep::Vec2;
using fixstep::World;

namespace {

using fixstep::bench::FlushDenormals;

// --- fixstep ---------------------------------------------------------------------------

template <class Real>
class FixstepStepper final : public Peer {
 public:
  FixstepStepper(const Scene& s, double dt, int threads, bool track)
      : w_(make_world<Real>(s, {.dt = dt, .track_dissipation = track, .threads = threads})) {
    for (const BodyDef& d : s.bodies) mass_.push_back(d.body.mass);
  }
  void step() override { w_->step(); }
  void state(std::span<Body> out) const override {
    for (std::size_t j = 0; j < out.size(); ++j) {
      out[j] = {mass_[j],
                {double(w_->x()[j]), double(w_->y()[j])},
                {double(w_->vx()[j]), double(w_->vy()[j])}};
    }
  }
  [[nodiscard]] double dissipated() const override { return w_->dissipated_energy(); }
  [[nodiscard]] int threads_used() const override { return w_->threads_used(); }

 private:
  std::unique_ptr<fixstep::detail::WorldKernel<Real>> w_;
  std::vector<double> mass_;
};

// --- the hand-written edge-list loop ------------------------------------------------------

/// Semi-implicit Euler over an edge list, as a programmer writes it: link forces scattered
/// into per-body accumulators in link order, then one pass over the bodies. The per-body
/// field is held as the engine holds it (K = k/m, γ = b/m, c = F/m computed in double and
/// rounded once; 1/m rounded once), and a term no body has is left out, as the engine's
/// compiled passes leave it out (so even the signs of zeros agree).
template <class Real>
class EdgeLoop final : public Peer {
 public:
  EdgeLoop(const Scene& s, double dt) : h_(Real(dt)) {
    for (const BodyDef& d : s.bodies) {
      const double m = d.body.mass;
      mass_.push_back(m);
      x_.push_back(Real(d.body.position.x)), y_.push_back(Real(d.body.position.y));
      vx_.push_back(Real(d.body.velocity.x)), vy_.push_back(Real(d.body.velocity.y));
      const SpringDamper sp = d.spring.value_or(SpringDamper{});
      k_.push_back(Real(sp.stiffness / m)), gamma_.push_back(Real(sp.damping / m));
      ax0_.push_back(Real(sp.anchor.x)), ay0_.push_back(Real(sp.anchor.y));
      const Vec2 f = d.constant_force ? d.constant_force->force : Vec2{};
      cx_.push_back(Real(f.x / m)), cy_.push_back(Real(f.y / m));
      inv_m_.push_back(Real(1.0 / m));
      accel_ = accel_ || cx_.back() != Real(0) || cy_.back() != Real(0);
      damped_ = damped_ || gamma_.back() != Real(0);
    }
    for (const BodyLink& l : s.links) {
      a_.push_back(std::uint32_t(l.body_a)), b_.push_back(std::uint32_t(l.body_b));
      lk_.push_back(Real(l.spring.stiffness)), lb_.push_back(Real(l.spring.damping));
      link_damped_ = link_damped_ || lb_.back() != Real(0);
    }
    acc_x_.resize(x_.size()), acc_y_.resize(x_.size());
  }
  void step() override {
    const FlushDenormals ftz;
    if (link_damped_) {
      if (accel_)
        damped_ ? tick<true, true, true>() : tick<true, false, true>();
      else
        damped_ ? tick<false, true, true>() : tick<false, false, true>();
    } else {
      if (accel_)
        damped_ ? tick<true, true, false>() : tick<true, false, false>();
      else
        damped_ ? tick<false, true, false>() : tick<false, false, false>();
    }
  }
  void state(std::span<Body> out) const override {
    for (std::size_t j = 0; j < out.size(); ++j) {
      out[j] = {mass_[j], {double(x_[j]), double(y_[j])}, {double(vx_[j]), double(vy_[j])}};
    }
  }

 private:
  template <bool Accel, bool Damped, bool LinkDamped>
  void tick() {
    const std::size_t n = x_.size(), m = a_.size();
    Real* __restrict ax = acc_x_.data();
    Real* __restrict ay = acc_y_.data();
    const Real* __restrict x = x_.data();
    const Real* __restrict y = y_.data();
    const Real* __restrict vx = vx_.data();
    const Real* __restrict vy = vy_.data();
    std::fill(acc_x_.begin(), acc_x_.end(), Real(0));
    std::fill(acc_y_.begin(), acc_y_.end(), Real(0));
    for (std::size_t l = 0; l < m; ++l) {
      const std::uint32_t a = a_[l], b = b_[l];
      const Real dx = x[a] - x[b], dy = y[a] - y[b];
      Real fx = -lk_[l] * dx, fy = -lk_[l] * dy;
      if constexpr (LinkDamped) {
        const Real ux = vx[a] - vx[b], uy = vy[a] - vy[b];
        fx -= lb_[l] * ux, fy -= lb_[l] * uy;
      }
      ax[a] += fx, ay[a] += fy;
      ax[b] -= fx, ay[b] -= fy;
    }
    update<Accel, Damped>(n, x_.data(), y_.data(), vx_.data(), vy_.data());
  }
  template <bool Accel, bool Damped>
  void update(std::size_t n, Real* __restrict x, Real* __restrict y, Real* __restrict vx,
              Real* __restrict vy) {
    const Real h = h_;
    const Real* __restrict k = k_.data();
    const Real* __restrict ax0 = ax0_.data();
    const Real* __restrict ay0 = ay0_.data();
    const Real* __restrict g = gamma_.data();
    const Real* __restrict cx = cx_.data();
    const Real* __restrict cy = cy_.data();
    const Real* __restrict im = inv_m_.data();
    const Real* __restrict fx = acc_x_.data();
    const Real* __restrict fy = acc_y_.data();
    for (std::size_t j = 0; j < n; ++j) {
      Real ax = -k[j] * (x[j] - ax0[j]), ay = -k[j] * (y[j] - ay0[j]);
      if constexpr (Accel) ax += cx[j], ay += cy[j];
      if constexpr (Damped) ax -= g[j] * vx[j], ay -= g[j] * vy[j];
      ax += im[j] * fx[j], ay += im[j] * fy[j];
      vx[j] += ax * h, vy[j] += ay * h;
      x[j] += vx[j] * h, y[j] += vy[j] * h;
    }
  }
  Real h_;
  std::vector<Real> x_, y_, vx_, vy_;
  std::vector<Real> k_, ax0_, ay0_, gamma_, cx_, cy_, inv_m_, acc_x_, acc_y_, lk_, lb_;
  std::vector<std::uint32_t> a_, b_;
  std::vector<double> mass_;
  bool accel_ = false, damped_ = false, link_damped_ = false;
};

}  // namespace

std::unique_ptr<Peer> make_stepper(const std::string& key, const Scene& s, double dt, bool track) {
  if (key == "fixstep_f64_t1" || key == "fixstep_f64")
    return std::make_unique<FixstepStepper<double>>(s, dt, 1, track);
  if (key == "fixstep_f64_t2") return std::make_unique<FixstepStepper<double>>(s, dt, 2, track);
  if (key == "fixstep_f32_t1" || key == "fixstep_f32")
    return std::make_unique<FixstepStepper<float>>(s, dt, 1, track);
  if (key == "fixstep_f32_t2") return std::make_unique<FixstepStepper<float>>(s, dt, 2, track);
  if (key == "edge_f64") return std::make_unique<EdgeLoop<double>>(s, dt);
  if (key == "edge_f32") return std::make_unique<EdgeLoop<float>>(s, dt);
  if (key == "chipmunk") return make_chipmunk(s, dt);
  if (key == "box2d") return make_box2d(s, dt);
  throw std::invalid_argument("no stepper " + key);
}

}  // namespace coupled
