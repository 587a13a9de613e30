// Throughput of fixstep's stepping path against the machine's limits and against what a user
// would write or pick instead, in one run (Google Benchmark):
//   engine      the kernel's step (detail::WorldKernel<Real>::step(), the stepping path a
//               World holds) per integrator, f32/f64, spring-damper and projectile scenes, N = 10^2
//               ... 1.6·10^7 bodies;
//   world       the public fixstep::World's step (semi-implicit Euler, N <= 10^6): what the
//               interface adds to the kernel it holds;
//   raw         a fused loop over plain arrays doing the same arithmetic (the kernel bound);
//               checked bit for bit against the engine before anything is timed;
//   triad       STREAM's triad a = b + s·c (McCalpin, "Memory Bandwidth and Machine Balance
//               in Current High Performance Computers", IEEE TCCA Newsletter 1995): the
//               memory-bandwidth bound;
//   aos_virtual the naive layout: one heap object per body, a virtual step() per body;
//   odeint      Boost.Odeint's symplectic_euler and runge_kutta4 on the same systems at
//               N = 10^5 (answers checked against the engine first);
//   aging       a damped f32 scene's first 10^4 ticks against ticks 10^6 ... 10^6 + 10^4.
// After the run it prints (and with --report=FILE writes) the markdown tables of
// docs/PERFORMANCE.md and the targets as measured ratios of medians.
//
//   build/bench/bin/bench_throughput --report=docs/perf/throughput.md
//   build/bench/bin/bench_throughput --quick       (N <= 10^4, one repetition: a smoke run)
//   build/bench/bin/bench_throughput --verify-only (the equality checks alone; run by ctest)
//   build/bench/bin/bench_throughput --simd=baseline (time the SSE2 sweeps; default: widest)
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <algorithm>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "fixstep/capture/capture.hpp"
#include "fixstep/core/components.hpp"
#include "fixstep/core/simd.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "flush_denormals.hpp"
#include "median_run.hpp"
#include "simd_targets.hpp"
#include "world_kernel.hpp"

#if defined(__x86_64__) || defined(__i386__)
#include <xmmintrin.h>
#endif

using namespace fixstep;

namespace {

constexpr double dt = 1.0 / 60.0;  // s, the game default
enum class SceneKind { spring, projectile, undamped_spring };
const char* scene_name(SceneKind s) {
  return s == SceneKind::spring ? "spring" : s == SceneKind::projectile ? "projectile" : "undamped";
}

// --- the scenes: N bodies with varied parameters, the same for every contender ------------

/// Body j of a scene. Spring-damper: k = 1 ... 4 N/m, m = 1 ... 2 kg, b = 0.5 ... 0.7 N·s/m
/// (ω·dt <= 0.034, damped enough that even explicit Euler stays bounded: its growth per tick
/// 1 + (ω·dt)² is below the damping's e^{-γ dt}), anchors spread over 50 m x 26 m.
/// Projectile: m = 0.5 ... 1.4 kg, g = 9.81 m/s², drag c = 0 ... 0.15 N·s/m (a quarter of
/// the bodies fly in vacuum).
BodyDef body_def(SceneKind s, std::size_t j) {
  BodyDef d;
  if (s == SceneKind::projectile) {
    d.body.mass = 0.5 + 0.1 * double(j % 10);
    d.body.velocity = {10.0 + double(j % 7), 15.0 + double(j % 11)};
    d.gravity = Gravity{{0.0, -9.81}};
    if (j % 4 != 0) d.drag = LinearDrag{0.05 * double(j % 4)};
    return d;
  }
  d.body.mass = 1.0 + 0.25 * double(j % 5);
  const Vec2 anchor{0.5 * double(j % 101), 0.5 * double(j % 53)};
  d.body.position = {anchor.x + 1.0 + 0.1 * double(j % 11), anchor.y - 0.5 + 0.1 * double(j % 13)};
  d.body.velocity = {0.1 * double(j % 5), -0.2};
  d.spring =
      SpringDamper{.anchor = anchor,
                   .stiffness = 1.0 + 0.5 * double(j % 7),
                   .damping = s == SceneKind::undamped_spring ? 0.0 : 0.5 + 0.1 * double(j % 3)};
  return d;
}

template <class Real>
std::unique_ptr<fixstep::detail::WorldKernel<Real>> make_world(SceneKind s, std::size_t n,
                                                               Integrator integrator) {
  auto w = std::make_unique<fixstep::detail::WorldKernel<Real>>(
      WorldSettings{.dt = dt, .integrator = integrator});
  w->reserve(n);
  for (std::size_t j = 0; j < n; ++j) w->create_body(body_def(s, j));
  return w;
}

/// The contenders of the last benchmark, kept for the next one of the same scene, precision
/// and N: building 1.6·10^7 bodies takes seconds, and Google Benchmark calls a benchmark
/// function several times (to choose the iteration count, then per repetition). One object
/// per slot (engine world, raw arrays, naive objects) is alive at a time.
template <class T, class Make>
T& cached(int slot, const std::string& key, Make make) {
  struct Slot {
    std::string key;
    std::shared_ptr<void> object;
  };
  static Slot slots[4];
  Slot& c = slots[slot];
  if (c.key != key) {
    c.object.reset();
    c.object = std::shared_ptr<T>(make());
    c.key = key;
  }
  return *static_cast<T*>(c.object.get());
}

std::string cache_key(SceneKind s, std::size_t real, std::size_t n) {
  return fmt::format("{}/{}/{}", scene_name(s), real, n);
}

template <class Real>
fixstep::detail::WorldKernel<Real>& cached_world(SceneKind s, std::size_t n) {
  return cached<fixstep::detail::WorldKernel<Real>>(0, cache_key(s, sizeof(Real), n), [&] {
    return make_world<Real>(s, n, Integrator::semi_implicit_euler).release();
  });
}

// --- raw fused loops: what a programmer writes by hand for one scene ----------------------

/// The scene's per-body field in plain arrays, converted exactly as the engine converts its
/// components (K = k/m, γ = (b + c)/m and c = F/m + g summed in double, then rounded), so the
/// loops below must reproduce the engine's states bit for bit.
template <class Real>
struct RawBodies {
  bool spring = false, accel = false;
  std::vector<Real> x, y, vx, vy, k, ax0, ay0, gamma, cx, cy, decay_half, decay_h1, decay_h0;

  RawBodies(SceneKind s, std::size_t n) {
    for (std::size_t j = 0; j < n; ++j) {
      const BodyDef d = body_def(s, j);
      const double m = d.body.mass;
      x.push_back(Real(d.body.position.x)), y.push_back(Real(d.body.position.y));
      vx.push_back(Real(d.body.velocity.x)), vy.push_back(Real(d.body.velocity.y));
      double g = 0.0, ax = 0.0, ay = 0.0, kk = 0.0, cxx = 0.0, cyy = 0.0;
      if (d.spring) {
        spring = true;
        kk = d.spring->stiffness / m, g += d.spring->damping / m;
        ax = d.spring->anchor.x, ay = d.spring->anchor.y;
      }
      if (d.drag) g += d.drag->coefficient / m;
      if (d.gravity)
        accel = true, cxx += d.gravity->acceleration.x, cyy += d.gravity->acceleration.y;
      k.push_back(Real(kk)), ax0.push_back(Real(ax)), ay0.push_back(Real(ay));
      gamma.push_back(Real(g)), cx.push_back(Real(cxx)), cy.push_back(Real(cyy));
    }
    // Damping-flow factors e^{-γτ} for Verlet (τ = h/2) and Forest–Ruth (τ = w1·h/2, w0·h/2).
    const Real h = Real(dt);
    const Real h1 = Real(forest_ruth_w1 * double(h)), h0 = Real(forest_ruth_w0 * double(h));
    for (Real gj : gamma) {
      decay_half.push_back(Real(std::exp(-double(gj) * (0.5 * double(h)))));
      decay_h1.push_back(Real(std::exp(-double(gj) * (0.5 * double(h1)))));
      decay_h0.push_back(Real(std::exp(-double(gj) * (0.5 * double(h0)))));
    }
  }
};

/// One tick of `integrator` over every body of a spring-damper (Spring) or projectile scene,
/// written as one plain loop per integrator. The arrays are restrict-qualified parameters (no
/// overlap), so the compiler may vectorize each loop. Like the engine's sweeps, it is compiled
/// once per SimdLevel (raw_step picks the engine's level), so both sides use the same ISA.
#define RAW_LOOP_PARAMS                                                                    \
  Integrator integrator, std::size_t n, Real *__restrict x, Real *__restrict y,            \
      Real *__restrict vx, Real *__restrict vy, const Real *__restrict k,                  \
      const Real *__restrict ax0, const Real *__restrict ay0, const Real *__restrict g,    \
      const Real *__restrict cx, const Real *__restrict cy, const Real *__restrict d_half, \
      const Real *__restrict d_h1, const Real *__restrict d_h0
#define RAW_LOOP_ARGS integrator, n, x, y, vx, vy, k, ax0, ay0, g, cx, cy, d_half, d_h1, d_h0
template <bool Spring, class Real>
[[gnu::always_inline]] inline void raw_loop(RAW_LOOP_PARAMS) {
  const Real h = Real(dt), half = h * Real(0.5);
  switch (integrator) {
    case Integrator::semi_implicit_euler:
      for (std::size_t j = 0; j < n; ++j) {
        Real ax, ay;
        if constexpr (Spring)
          ax = -k[j] * (x[j] - ax0[j]), ay = -k[j] * (y[j] - ay0[j]);
        else
          ax = cx[j], ay = cy[j];
        ax -= g[j] * vx[j], ay -= g[j] * vy[j];
        vx[j] += ax * h, vy[j] += ay * h;
        x[j] += vx[j] * h, y[j] += vy[j] * h;
      }
      break;
    case Integrator::explicit_euler:
      for (std::size_t j = 0; j < n; ++j) {
        Real ax, ay;
        if constexpr (Spring)
          ax = -k[j] * (x[j] - ax0[j]), ay = -k[j] * (y[j] - ay0[j]);
        else
          ax = cx[j], ay = cy[j];
        ax -= g[j] * vx[j], ay -= g[j] * vy[j];
        x[j] += vx[j] * h, y[j] += vy[j] * h;
        vx[j] += ax * h, vy[j] += ay * h;
      }
      break;
    case Integrator::velocity_verlet:
      for (std::size_t j = 0; j < n; ++j) {
        const Real kj = Spring ? k[j] : Real(0), axj = Spring ? ax0[j] : Real(0);
        const Real ayj = Spring ? ay0[j] : Real(0);
        const Real cxj = Spring ? Real(0) : cx[j], cyj = Spring ? Real(0) : cy[j], d = d_half[j];
        Real px = x[j], py = y[j], ux = vx[j] * d, uy = vy[j] * d, ax, ay;
        if constexpr (Spring)
          ax = -kj * (px - axj), ay = -kj * (py - ayj);
        else
          ax = cxj, ay = cyj;
        ux += ax * half, uy += ay * half;
        px += ux * h, py += uy * h;
        if constexpr (Spring)
          ax = -kj * (px - axj), ay = -kj * (py - ayj);
        else
          ax = cxj, ay = cyj;
        ux += ax * half, uy += ay * half;
        x[j] = px, y[j] = py, vx[j] = ux * d, vy[j] = uy * d;
      }
      break;
    case Integrator::forest_ruth: {
      const Real h1 = Real(forest_ruth_w1 * double(h));
      const Real h0 = Real(forest_ruth_w0 * double(h));
      for (std::size_t j = 0; j < n; ++j) {
        const Real kj = Spring ? k[j] : Real(0), axj = Spring ? ax0[j] : Real(0);
        const Real ayj = Spring ? ay0[j] : Real(0);
        const Real cxj = Spring ? Real(0) : cx[j], cyj = Spring ? Real(0) : cy[j];
        const Real d1 = d_h1[j], d0 = d_h0[j];
        Real px = x[j], py = y[j], ux = vx[j], uy = vy[j], ax, ay;
        const Real hs[3] = {h1, h0, h1}, ds[3] = {d1, d0, d1};
        for (int stage = 0; stage < 3; ++stage) {  // Verlet steps of h1, h0, h1
          ux *= ds[stage], uy *= ds[stage];
          if constexpr (Spring)
            ax = -kj * (px - axj), ay = -kj * (py - ayj);
          else
            ax = cxj, ay = cyj;
          ux += ax * (hs[stage] * Real(0.5)), uy += ay * (hs[stage] * Real(0.5));
          px += ux * hs[stage], py += uy * hs[stage];
          if constexpr (Spring)
            ax = -kj * (px - axj), ay = -kj * (py - ayj);
          else
            ax = cxj, ay = cyj;
          ux += ax * (hs[stage] * Real(0.5)), uy += ay * (hs[stage] * Real(0.5));
          ux *= ds[stage], uy *= ds[stage];
        }
        x[j] = px, y[j] = py, vx[j] = ux, vy[j] = uy;
      }
      break;
    }
    case Integrator::rk4:
      for (std::size_t j = 0; j < n; ++j) {
        const Real kj = Spring ? k[j] : Real(0), axj = Spring ? ax0[j] : Real(0);
        const Real ayj = Spring ? ay0[j] : Real(0);
        const Real cxj = Spring ? Real(0) : cx[j], cyj = Spring ? Real(0) : cy[j], gj = g[j];
        const Real px = x[j], py = y[j], ux = vx[j], uy = vy[j];
        auto a = [&](Real qx, Real qy, Real wx, Real wy, Real& ax, Real& ay) {
          if constexpr (Spring)
            ax = -kj * (qx - axj), ay = -kj * (qy - ayj);
          else
            ax = cxj, ay = cyj;
          ax -= gj * wx, ay -= gj * wy;
        };
        Real k1x, k1y, k2x, k2y, k3x, k3y, k4x, k4y;
        a(px, py, ux, uy, k1x, k1y);
        const Real v2x = ux + half * k1x, v2y = uy + half * k1y;
        a(px + half * ux, py + half * uy, v2x, v2y, k2x, k2y);
        const Real v3x = ux + half * k2x, v3y = uy + half * k2y;
        a(px + half * v2x, py + half * v2y, v3x, v3y, k3x, k3y);
        const Real v4x = ux + h * k3x, v4y = uy + h * k3y;
        a(px + h * v3x, py + h * v3y, v4x, v4y, k4x, k4y);
        const Real sixth = h / Real(6);
        x[j] = px + sixth * (((ux + Real(2) * v2x) + Real(2) * v3x) + v4x);
        y[j] = py + sixth * (((uy + Real(2) * v2y) + Real(2) * v3y) + v4y);
        vx[j] = ux + sixth * (((k1x + Real(2) * k2x) + Real(2) * k3x) + k4x);
        vy[j] = uy + sixth * (((k1y + Real(2) * k2y) + Real(2) * k3y) + k4y);
      }
      break;
    case Integrator::implicit_euler:
      // Backward Euler, linear forces: v' = (v + h a_c(x)) / (1 + hγ + h²K), x' = x + h v'.
      for (std::size_t j = 0; j < n; ++j) {
        Real denom = Real(1) + h * g[j], ux, uy;
        if constexpr (Spring) {
          denom += h * h * k[j];
          ux = (vx[j] + h * (-k[j] * (x[j] - ax0[j]))) / denom;
          uy = (vy[j] + h * (-k[j] * (y[j] - ay0[j]))) / denom;
        } else {
          ux = (vx[j] + h * cx[j]) / denom, uy = (vy[j] + h * cy[j]) / denom;
        }
        vx[j] = ux, vy[j] = uy;
        x[j] += h * ux, y[j] += h * uy;
      }
      break;
  }
}

template <bool Spring, class Real>
void raw_loop_baseline(RAW_LOOP_PARAMS) {
  raw_loop<Spring>(RAW_LOOP_ARGS);
}
#if FIXSTEP_HAS_SIMD_CLONES
template <bool Spring, class Real>
FIXSTEP_TARGET_AVX2 void raw_loop_avx2(RAW_LOOP_PARAMS) {
  raw_loop<Spring>(RAW_LOOP_ARGS);
}
template <bool Spring, class Real>
FIXSTEP_TARGET_AVX512 void raw_loop_avx512(RAW_LOOP_PARAMS) {
  raw_loop<Spring>(RAW_LOOP_ARGS);
}
#endif
template <bool Spring, class Real>
void raw_loop_at(SimdLevel level, RAW_LOOP_PARAMS) {
#if FIXSTEP_HAS_SIMD_CLONES
  if (level == SimdLevel::avx512) return raw_loop_avx512<Spring>(RAW_LOOP_ARGS);
  if (level == SimdLevel::avx2) return raw_loop_avx2<Spring>(RAW_LOOP_ARGS);
#endif
  (void)level;
  raw_loop_baseline<Spring>(RAW_LOOP_ARGS);
}
#undef RAW_LOOP_PARAMS
#undef RAW_LOOP_ARGS

template <bool Spring, class Real>
void raw_step(RawBodies<Real>& r, Integrator i) {
  raw_loop_at<Spring>(simd_level(), i, r.x.size(), r.x.data(), r.y.data(), r.vx.data(), r.vy.data(),
                      r.k.data(), r.ax0.data(), r.ay0.data(), r.gamma.data(), r.cx.data(),
                      r.cy.data(), r.decay_half.data(), r.decay_h1.data(), r.decay_h0.data());
}

template <class Real>
void raw_step(SceneKind s, RawBodies<Real>& r, Integrator i) {
  if (s == SceneKind::projectile)
    raw_step<false>(r, i);
  else
    raw_step<true>(r, i);
}

using fixstep::bench::FlushDenormals;

// --- the naive baseline: array of heap objects, a virtual call per body -------------------

template <class Real>
struct NaiveBody {
  virtual ~NaiveBody() = default;
  virtual void step(Real h) = 0;  // semi-implicit Euler
  Real x, y, vx, vy, mass;
};
template <class Real>
struct NaiveSpring final : NaiveBody<Real> {
  Real k, b, anchor_x, anchor_y;
  void step(Real h) override {
    const Real fx = -k * (this->x - anchor_x) - b * this->vx;
    const Real fy = -k * (this->y - anchor_y) - b * this->vy;
    this->vx += fx / this->mass * h, this->vy += fy / this->mass * h;
    this->x += this->vx * h, this->y += this->vy * h;
  }
};
template <class Real>
struct NaiveProjectile final : NaiveBody<Real> {
  Real drag, gx, gy;
  void step(Real h) override {
    this->vx += (-drag * this->vx / this->mass + gx) * h;
    this->vy += (-drag * this->vy / this->mass + gy) * h;
    this->x += this->vx * h, this->y += this->vy * h;
  }
};
template <class Real>
std::vector<std::unique_ptr<NaiveBody<Real>>> naive_bodies(SceneKind s, std::size_t n) {
  std::vector<std::unique_ptr<NaiveBody<Real>>> out;
  out.reserve(n);
  for (std::size_t j = 0; j < n; ++j) {
    const BodyDef d = body_def(s, j);
    std::unique_ptr<NaiveBody<Real>> b;
    if (d.spring) {
      auto sp = std::make_unique<NaiveSpring<Real>>();
      sp->k = Real(d.spring->stiffness), sp->b = Real(d.spring->damping);
      sp->anchor_x = Real(d.spring->anchor.x), sp->anchor_y = Real(d.spring->anchor.y);
      b = std::move(sp);
    } else {
      auto p = std::make_unique<NaiveProjectile<Real>>();
      p->drag = Real(d.drag ? d.drag->coefficient : 0.0);
      p->gx = Real(d.gravity->acceleration.x), p->gy = Real(d.gravity->acceleration.y);
      b = std::move(p);
    }
    b->x = Real(d.body.position.x), b->y = Real(d.body.position.y);
    b->vx = Real(d.body.velocity.x), b->vy = Real(d.body.velocity.y);
    b->mass = Real(d.body.mass);
    out.push_back(std::move(b));
  }
  return out;
}

// --- Boost.Odeint on the same systems ----------------------------------------------------

namespace odeint = boost::numeric::odeint;
using OdeState = std::vector<double>;  // x[N], y[N], vx[N], vy[N]

/// x' = v, v' = -K (x - anchor) - γ v with the engine's K and γ: the spring scene as one ODE.
struct SpringSystem {
  const RawBodies<double>* r;
  void operator()(const OdeState& s, OdeState& dsdt, double /*t*/) const {
    const std::size_t n = r->x.size();
    for (std::size_t j = 0; j < n; ++j) {
      dsdt[j] = s[2 * n + j];
      dsdt[n + j] = s[3 * n + j];
      dsdt[2 * n + j] = -r->k[j] * (s[j] - r->ax0[j]) - r->gamma[j] * s[2 * n + j];
      dsdt[3 * n + j] = -r->k[j] * (s[n + j] - r->ay0[j]) - r->gamma[j] * s[3 * n + j];
    }
  }
};
OdeState ode_state(const RawBodies<double>& r) {
  OdeState s;
  for (const auto* v : {&r.x, &r.y, &r.vx, &r.vy}) s.insert(s.end(), v->begin(), v->end());
  return s;
}

/// The undamped spring scene for odeint's symplectic_euler: q = (x, y), p = (vx, vy) (unit
/// "mass" in odeint's sense: q' = p). Its momentum function is dp/dt = a_c(q). Passed alone,
/// it is odeint's SimpleSymplecticSystem: odeint then adds dt·p to q itself, with no
/// coordinate function and no copy (its fastest form for this system).
struct UndampedMomentum {
  const RawBodies<double>* r;
  void operator()(const OdeState& q, OdeState& dpdt) const {
    const std::size_t n = r->x.size();
    for (std::size_t j = 0; j < n; ++j) {
      dpdt[j] = -r->k[j] * (q[j] - r->ax0[j]);
      dpdt[n + j] = -r->k[j] * (q[n + j] - r->ay0[j]);
    }
  }
};

// --- checks before timing: every contender gives the engine's answers ---------------------

int check_failures = 0;
void check(bool ok, const std::string& what) {
  if (!ok) {
    std::fprintf(stderr, "CHECK FAILED: %s\n", what.c_str());
    ++check_failures;
  }
}

/// The engine and the raw loop, each at `level`, against the raw loop at the baseline level:
/// every SIMD level must give the same bits, and the raw loop the engine's bits.
template <class Real>
void verify_raw(SceneKind s, Integrator i, SimdLevel level) {
  constexpr std::size_t n = 1001;  // odd: the vector loops' scalar remainders run too
  constexpr int ticks = 200;
  auto raw_at = [&](SimdLevel l) {
    set_simd_level(l);
    RawBodies<Real> r(s, n);
    const FlushDenormals ftz;
    for (int t = 0; t < ticks; ++t) raw_step(s, r, i);
    return r;
  };
  const RawBodies<Real> reference = raw_at(SimdLevel::baseline);
  const RawBodies<Real> raw = raw_at(level);
  auto w = make_world<Real>(s, n, i);
  for (int t = 0; t < ticks; ++t) w->step();
  std::size_t engine_differ = 0, raw_differ = 0;
  for (std::size_t j = 0; j < n; ++j) {
    engine_differ += !(w->x()[j] == reference.x[j] && w->y()[j] == reference.y[j] &&
                       w->vx()[j] == reference.vx[j] && w->vy()[j] == reference.vy[j]);
    raw_differ += !(raw.x[j] == reference.x[j] && raw.y[j] == reference.y[j] &&
                    raw.vx[j] == reference.vx[j] && raw.vy[j] == reference.vy[j]);
  }
  const auto what = fmt::format("{}/f{}/{} at SIMD level {}", scene_name(s), 8 * sizeof(Real),
                                integrator_name(i), simd_level_name(level));
  check(engine_differ == 0, fmt::format("engine {}: {} of {} bodies differ from the baseline raw "
                                        "loop after {} ticks (the loops must do the same "
                                        "arithmetic)",
                                        what, engine_differ, n, ticks));
  check(raw_differ == 0, fmt::format("raw {}: {} of {} bodies differ from the baseline raw loop "
                                     "after {} ticks",
                                     what, raw_differ, n, ticks));
}

void verify_odeint() {
  constexpr std::size_t n = 1000;
  constexpr int ticks = 200;
  {  // runge_kutta4 on the damped spring scene vs the engine's RK4, f64.
    auto w = make_world<double>(SceneKind::spring, n, Integrator::rk4);
    RawBodies<double> r(SceneKind::spring, n);
    OdeState s = ode_state(r);
    odeint::runge_kutta4<OdeState> rk4;
    for (int t = 0; t < ticks; ++t) rk4.do_step(SpringSystem{&r}, s, t * dt, dt), w->step();
    double worst = 0.0;
    for (std::size_t j = 0; j < n; ++j) {
      worst = std::max({worst, std::abs(s[j] - w->x()[j]), std::abs(s[n + j] - w->y()[j]),
                        std::abs(s[2 * n + j] - w->vx()[j]), std::abs(s[3 * n + j] - w->vy()[j])});
    }
    check(worst <= 1e-11, fmt::format("odeint runge_kutta4 vs engine rk4: max |difference| "
                                      "{:.3e} > 1e-11 (m, m/s)",
                                      worst));
  }
  {  // symplectic_euler (position first) vs the engine's semi-implicit Euler (velocity first):
     // started from (x0, v0 + a(x0) dt), odeint's (q_n, p_n) is the engine's (x_n, v_{n+1}).
    auto w = make_world<double>(SceneKind::undamped_spring, n, Integrator::semi_implicit_euler);
    RawBodies<double> r(SceneKind::undamped_spring, n);
    OdeState q(2 * n), p(2 * n);
    for (std::size_t j = 0; j < n; ++j) {
      q[j] = r.x[j], q[n + j] = r.y[j];
      p[j] = r.vx[j] + dt * (-r.k[j] * (r.x[j] - r.ax0[j]));
      p[n + j] = r.vy[j] + dt * (-r.k[j] * (r.y[j] - r.ay0[j]));
    }
    odeint::symplectic_euler<OdeState> euler;
    for (int t = 0; t < ticks; ++t) {
      euler.do_step(UndampedMomentum{&r}, std::make_pair(std::ref(q), std::ref(p)), t * dt, dt);
      w->step();
    }
    double worst = 0.0;
    for (std::size_t j = 0; j < n; ++j) {
      worst = std::max({worst, std::abs(q[j] - w->x()[j]), std::abs(q[n + j] - w->y()[j])});
    }
    check(worst <= 1e-11, fmt::format("odeint symplectic_euler vs engine semi-implicit Euler: "
                                      "max |position difference| {:.3e} > 1e-11 m",
                                      worst));
  }
}

// --- benchmarks ---------------------------------------------------------------------------

void set_rates(benchmark::State& st, std::size_t n, std::size_t bytes_per_body_step) {
  const auto items = static_cast<std::int64_t>(st.iterations()) * static_cast<std::int64_t>(n);
  st.SetItemsProcessed(items);
  st.SetBytesProcessed(items * static_cast<std::int64_t>(bytes_per_body_step));
  st.counters["N"] = double(n);
  st.counters["bytes_per_body_step"] = double(bytes_per_body_step);
}

template <class Real>
void bm_engine(benchmark::State& st, SceneKind s, Integrator i) {
  const auto n = static_cast<std::size_t>(st.range(0));
  fixstep::detail::WorldKernel<Real>& w = cached_world<Real>(s, n);
  w.set_integrator(i);
  w.step();
  for (auto _ : st) {
    w.step();
    benchmark::ClobberMemory();
  }
  set_rates(st, n, w.bytes_per_body_step());
}

/// The same step through the public fixstep::World (the precision inside, chosen at
/// creation): what a program holds. Against engine/ (the kernel it holds), in the same
/// run, it measures what the public interface adds per tick.
template <class Real>
void bm_world(benchmark::State& st, SceneKind s) {
  const auto n = static_cast<std::size_t>(st.range(0));
  auto& w = cached<fixstep::World>(3, cache_key(s, sizeof(Real), n), [&] {
    auto* world = new fixstep::World(fixstep::WorldDef::empty(
        sizeof(Real) == 4 ? Precision::f32 : Precision::f64, WorldSettings{.dt = dt}));
    for (std::size_t j = 0; j < n; ++j) world->create_body(body_def(s, j));
    return world;
  });
  w.step();
  for (auto _ : st) {
    w.step();
    benchmark::ClobberMemory();
  }
  set_rates(st, n, make_world<Real>(s, 1, Integrator::semi_implicit_euler)->bytes_per_body_step());
}

/// Bytes per body-step of the raw loops: the arrays each reads and writes (as the engine
/// counts them).
std::size_t raw_bytes(SceneKind s, Integrator i, std::size_t real) {
  std::size_t arrays = 8;
  arrays += s == SceneKind::projectile ? 2 : 3;    // c | K, anchor
  arrays += i == Integrator::forest_ruth ? 2 : 1;  // γ or the damping-flow factors
  return arrays * real;
}

template <class Real>
void bm_raw(benchmark::State& st, SceneKind s, Integrator i) {
  const auto n = static_cast<std::size_t>(st.range(0));
  auto& r = cached<RawBodies<Real>>(1, cache_key(s, sizeof(Real), n),
                                    [&] { return new RawBodies<Real>(s, n); });
  const FlushDenormals ftz;
  for (auto _ : st) {
    raw_step(s, r, i);
    benchmark::ClobberMemory();
  }
  set_rates(st, n, raw_bytes(s, i, sizeof(Real)));
}

/// STREAM's triad, a = b + s·c, compiled per SimdLevel like the sweeps.
template <class Real>
[[gnu::always_inline]] inline void triad_loop(std::size_t n, Real* __restrict a,
                                              const Real* __restrict b, const Real* __restrict c,
                                              Real s) {
  for (std::size_t j = 0; j < n; ++j) a[j] = b[j] + s * c[j];
}
template <class Real>
void triad_baseline(std::size_t n, Real* a, const Real* b, const Real* c, Real s) {
  triad_loop(n, a, b, c, s);
}
#if FIXSTEP_HAS_SIMD_CLONES
template <class Real>
FIXSTEP_TARGET_AVX2 void triad_avx2(std::size_t n, Real* a, const Real* b, const Real* c, Real s) {
  triad_loop(n, a, b, c, s);
}
template <class Real>
FIXSTEP_TARGET_AVX512 void triad_avx512(std::size_t n, Real* a, const Real* b, const Real* c,
                                        Real s) {
  triad_loop(n, a, b, c, s);
}
#endif
template <class Real>
void triad(std::size_t n, Real* a, const Real* b, const Real* c, Real s) {
#if FIXSTEP_HAS_SIMD_CLONES
  if (simd_level() == SimdLevel::avx512) return triad_avx512(n, a, b, c, s);
  if (simd_level() == SimdLevel::avx2) return triad_avx2(n, a, b, c, s);
#endif
  triad_baseline(n, a, b, c, s);
}

template <class Real>
void bm_triad(benchmark::State& st) {
  const auto n = static_cast<std::size_t>(st.range(0));
  std::vector<Real> a(n, Real(0)), b(n, Real(1)), c(n, Real(2));
  const Real scalar = Real(3);
  for (auto _ : st) {
    triad(n, a.data(), b.data(), c.data(), scalar);
    benchmark::ClobberMemory();
  }
  benchmark::DoNotOptimize(a.data());
  set_rates(st, n, 3 * sizeof(Real));
}

template <class Real>
void bm_aos_virtual(benchmark::State& st, SceneKind s) {
  const auto n = static_cast<std::size_t>(st.range(0));
  using Bodies = std::vector<std::unique_ptr<NaiveBody<Real>>>;
  auto& bodies = cached<Bodies>(2, cache_key(s, sizeof(Real), n),
                                [&] { return new Bodies(naive_bodies<Real>(s, n)); });
  const FlushDenormals ftz;
  for (auto _ : st) {
    for (auto& b : bodies) b->step(Real(dt));
    benchmark::ClobberMemory();
  }
  // x, y, vx, vy read and written + the body's parameters (4 spring or 3 projectile + mass)
  // + the vtable pointer, as the engine counts: every field touched once.
  const std::size_t fields = 8 + (s == SceneKind::projectile ? 4 : 5);
  set_rates(st, n, fields * sizeof(Real) + sizeof(void*));
}

void bm_odeint_rk4(benchmark::State& st) {
  const auto n = static_cast<std::size_t>(st.range(0));
  RawBodies<double> r(SceneKind::spring, n);
  OdeState s = ode_state(r);
  odeint::runge_kutta4<OdeState> rk4;
  double t = 0.0;
  for (auto _ : st) {
    rk4.do_step(SpringSystem{&r}, s, t, dt);
    t += dt;
    benchmark::ClobberMemory();
  }
  set_rates(st, n, 0);
}

void bm_odeint_symplectic_euler(benchmark::State& st) {
  const auto n = static_cast<std::size_t>(st.range(0));
  RawBodies<double> r(SceneKind::undamped_spring, n);
  OdeState q(2 * n), p(2 * n);
  for (std::size_t j = 0; j < n; ++j)
    q[j] = r.x[j], q[n + j] = r.y[j], p[j] = r.vx[j], p[n + j] = r.vy[j];
  odeint::symplectic_euler<OdeState> euler;
  double t = 0.0;
  for (auto _ : st) {
    euler.do_step(UndampedMomentum{&r}, std::make_pair(std::ref(q), std::ref(p)), t, dt);
    t += dt;
    benchmark::ClobberMemory();
  }
  set_rates(st, n, 0);
}

/// A strongly damped f32 spring scene (k = 100 N/m, b = 20 N·s/m, m = 1 kg: ζ = 1, amplitude
/// e^{-10 t}) stepped for `ticks` ticks, timed from tick `from` on (the ticks before are
/// setup). Aged (from = 10^6) against fresh (from = 0) shows what subnormals would cost.
///
/// Both cases do the same untimed work first: the aged world steps its 10^6 ticks; the fresh
/// case steps a second, identical world 10^6 ticks and then times a new one. So the CPU is in
/// the same state (clock, vector-unit power licence) when the timed ticks start, and only the
/// state of the timed world differs.
void bm_aging(benchmark::State& st) {
  const auto from = static_cast<std::uint64_t>(st.range(0));
  const bool flush = st.range(1) != 0;
  constexpr std::size_t n = 1000;
  constexpr int ticks = 10'000;
  constexpr std::uint64_t warm_ticks = 1'000'000;
  auto make = [&] {
    auto w = std::make_unique<fixstep::detail::WorldKernel<float>>(
        WorldSettings{.dt = 0.01, .flush_denormals = flush});
    for (std::size_t j = 0; j < n; ++j) {
      BodyDef d;
      d.body.position = {1.0 + 0.001 * double(j), 0.5};
      d.spring = SpringDamper{.anchor = {}, .stiffness = 100.0, .damping = 20.0};
      w->create_body(d);
    }
    return w;
  };
  for (auto _ : st) {
    st.PauseTiming();
    auto w = make();
    if (from > 0) {
      for (std::uint64_t t = 0; t < from; ++t) w->step();
    } else {
      auto warm = make();  // the same preceding work on another world
      for (std::uint64_t t = 0; t < warm_ticks; ++t) warm->step();
      benchmark::DoNotOptimize(warm->x().data());
    }
    st.ResumeTiming();
    for (int t = 0; t < ticks; ++t) w->step();
    benchmark::DoNotOptimize(w->x().data());
  }
  set_rates(st, n * ticks, 8 * sizeof(float) + 4 * sizeof(float));
}

// --- registration and the report ---------------------------------------------------------

struct Options {
  bool quick = false, verify_only = false;
  std::optional<std::string> report;
  SimdLevel simd = simd_level();  ///< --simd=baseline|avx2|avx512: the level timed
};

std::vector<std::int64_t> sizes(const Options& o) {
  if (o.quick) return {100, 1000, 4096, 10'000};
  return {100, 1000, 4096, 10'000, 100'000, 1'000'000, 16'000'000};
}

void register_all(const Options& o) {
  const int reps = o.quick ? 1 : 5;
  const double min_time = o.quick ? 0.02 : 0.1;
  auto tune = [&](benchmark::internal::Benchmark* b, std::int64_t n) {
    b->Arg(n)->Unit(benchmark::kNanosecond)->MinTime(min_time)->UseRealTime();
    if (reps > 1) b->Repetitions(reps)->ReportAggregatesOnly(true);
  };
  for (SceneKind s : {SceneKind::spring, SceneKind::projectile}) {
    for (std::int64_t n : sizes(o)) {
      for (const char* prec : {"f32", "f64"}) {
        const bool f64 = prec[1] == '6';
        for (Integrator i : all_integrators) {
          const auto name = fmt::format("{}/{}/{}", scene_name(s), prec, integrator_name(i));
          tune(benchmark::RegisterBenchmark(("engine/" + name).c_str(),
                                            [=](benchmark::State& st) {
                                              f64 ? bm_engine<double>(st, s, i)
                                                  : bm_engine<float>(st, s, i);
                                            }),
               n);
          tune(benchmark::RegisterBenchmark(("raw/" + name).c_str(),
                                            [=](benchmark::State& st) {
                                              f64 ? bm_raw<double>(st, s, i)
                                                  : bm_raw<float>(st, s, i);
                                            }),
               n);
        }
        if (n <= 1'000'000) {  // one more world in memory: not beside the 1.6·10^7-body ones
          tune(benchmark::RegisterBenchmark(
                   fmt::format("world/{}/{}/semi_implicit_euler", scene_name(s), prec).c_str(),
                   [=](benchmark::State& st) {
                     f64 ? bm_world<double>(st, s) : bm_world<float>(st, s);
                   }),
               n);
        }
        tune(benchmark::RegisterBenchmark(
                 fmt::format("aos_virtual/{}/{}/semi_implicit_euler", scene_name(s), prec).c_str(),
                 [=](benchmark::State& st) {
                   f64 ? bm_aos_virtual<double>(st, s) : bm_aos_virtual<float>(st, s);
                 }),
             n);
        if (s == SceneKind::spring) {
          tune(benchmark::RegisterBenchmark(
                   fmt::format("triad/{}", prec).c_str(),
                   [=](benchmark::State& st) { f64 ? bm_triad<double>(st) : bm_triad<float>(st); }),
               n);
        }
      }
    }
  }
  const std::int64_t peer_n = o.quick ? 10'000 : 100'000;
  tune(benchmark::RegisterBenchmark("odeint/spring/f64/runge_kutta4", bm_odeint_rk4), peer_n);
  tune(benchmark::RegisterBenchmark("engine/undamped/f64/semi_implicit_euler",
                                    [](benchmark::State& st) {
                                      bm_engine<double>(st, SceneKind::undamped_spring,
                                                        Integrator::semi_implicit_euler);
                                    }),
       peer_n);
  tune(benchmark::RegisterBenchmark("odeint/undamped/f64/symplectic_euler",
                                    bm_odeint_symplectic_euler),
       peer_n);
  if (!o.quick) {
    // Without the flush, ageing runs at subnormal speed (tens of ns per body-step): only the
    // flushed scene is aged the full 10^6 ticks; bench_float_hygiene shows the unflushed case.
    for (int flush : {1}) {
      for (std::int64_t from : {std::int64_t{0}, std::int64_t{1'000'000}}) {
        benchmark::RegisterBenchmark(fmt::format("aging/f32/flush:{}/from", flush).c_str(),
                                     bm_aging)
            ->Args({from, flush})
            ->Unit(benchmark::kMillisecond)
            ->Iterations(1)
            ->Repetitions(7)
            ->ReportAggregatesOnly(true)
            ->UseRealTime();
      }
    }
  }
}

/// Keeps the median real time (ns per iteration) and the counters of every benchmark
/// instance, keyed by its name without the aggregate suffix, e.g. "engine/spring/f64/rk4/4096".
class Collector : public benchmark::ConsoleReporter {
 public:
  struct Result {
    double ns = 0.0;     ///< real time per iteration, ns (median over repetitions)
    double n = 0.0;      ///< bodies
    double bytes = 0.0;  ///< bytes per body-step
    [[nodiscard]] double ns_per_body_step() const { return ns / n; }
    [[nodiscard]] double bandwidth() const { return bytes / ns_per_body_step(); }  ///< GB/s
  };
  std::map<std::string, Result> results;

  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& r : runs) {
      if (!fixstep::bench::median_or_single(r)) continue;
      Result res;
      res.ns = r.GetAdjustedRealTime() * (r.time_unit == benchmark::kMillisecond ? 1e6 : 1.0);
      if (auto it = r.counters.find("N"); it != r.counters.end()) res.n = it->second.value;
      if (auto it = r.counters.find("bytes_per_body_step"); it != r.counters.end()) {
        res.bytes = it->second.value;
      }
      results[r.run_name.function_name + "/" + r.run_name.args] = res;
    }
  }
  [[nodiscard]] const Result* find(const std::string& key) const {
    const auto it = results.find(key);
    return it == results.end() ? nullptr : &it->second;
  }
};

std::string si(double v) {
  if (v >= 1e6)
    return fmt::format("{:g}·10^{}", v / std::pow(10.0, std::floor(std::log10(v))),
                       int(std::floor(std::log10(v))));
  return fmt::format("{}", v);
}

std::string report(const Collector& c, const Options& o) {
  std::string out;
  auto line = [&out](const std::string& s) { out += s + "\n"; };
  const auto ns = sizes(o);
  const char* precs[] = {"f32", "f64"};
  line(
      fmt::format("Engine sweeps, raw loops and triad compiled for SIMD level **{}** "
                  "(fixstep/core/simd.hpp; chosen at run time, `--simd=` to force one).",
                  simd_level_name(o.simd)));

  for (SceneKind s : {SceneKind::spring, SceneKind::projectile}) {
    line(fmt::format("\n#### {} scene: ns per body-step (engine), median of repetitions\n",
                     s == SceneKind::spring ? "Spring-damper" : "Projectile"));
    std::string head = "| integrator | precision |", rule = "|---|---|";
    for (auto n : ns) head += fmt::format(" N = {} |", si(double(n))), rule += "---|";
    line(head), line(rule);
    for (Integrator i : all_integrators) {
      for (const char* p : precs) {
        std::string row = fmt::format("| `{}` | {} |", integrator_name(i), p);
        for (auto n : ns) {
          const auto* r =
              c.find(fmt::format("engine/{}/{}/{}/{}", scene_name(s), p, integrator_name(i), n));
          row += r ? fmt::format(" {:.3g} |", r->ns_per_body_step()) : " – |";
        }
        line(row);
      }
    }
    line(
        fmt::format("\n#### {} scene: engine speed as a fraction of the raw fused loop "
                    "(raw time / engine time)\n",
                    scene_name(s)));
    line(head), line(rule);
    for (Integrator i : all_integrators) {
      for (const char* p : precs) {
        std::string row = fmt::format("| `{}` | {} |", integrator_name(i), p);
        for (auto n : ns) {
          const auto key = fmt::format("{}/{}/{}/{}", scene_name(s), p, integrator_name(i), n);
          const auto *e = c.find("engine/" + key), *r = c.find("raw/" + key);
          row += e && r ? fmt::format(" {:.2f} |", r->ns / e->ns) : " – |";
        }
        line(row);
      }
    }
    line(
        fmt::format("\n#### {} scene: the naive array of objects with a virtual step() "
                    "(semi-implicit Euler), ns per body-step and engine speed-up\n",
                    scene_name(s)));
    line(head), line(rule);
    for (const char* p : precs) {
      std::string row = fmt::format("| naive AoS + virtual | {} |", p),
                  row2 = fmt::format("| speed-up of the engine | {} |", p),
                  row3 = fmt::format("| public World / kernel | {} |", p);
      for (auto n : ns) {
        const auto* a =
            c.find(fmt::format("aos_virtual/{}/{}/semi_implicit_euler/{}", scene_name(s), p, n));
        const auto* e =
            c.find(fmt::format("engine/{}/{}/semi_implicit_euler/{}", scene_name(s), p, n));
        const auto* w =
            c.find(fmt::format("world/{}/{}/semi_implicit_euler/{}", scene_name(s), p, n));
        row += a ? fmt::format(" {:.3g} |", a->ns_per_body_step()) : " – |";
        row2 += a && e ? fmt::format(" {:.1f}x |", a->ns / e->ns) : " – |";
        row3 += w && e ? fmt::format(" {:.3f} |", w->ns / e->ns) : " – |";
      }
      line(row), line(row2), line(row3);
    }
  }

  line("\n#### Memory bandwidth: bytes moved per body-step and the fraction of the triad bound\n");
  line("Bytes count every array element read or written once (STREAM's convention; the triad's");
  line("write-allocate traffic is not counted, as in STREAM). Triad = a[i] = b[i] + s·c[i] at the");
  line("same N, same precision.\n");
  line(
      "| scene | integrator | precision | bytes/body-step | N | engine GB/s | triad GB/s | "
      "fraction |");
  line("|---|---|---|---|---|---|---|---|");
  const std::int64_t big = ns.back();
  for (SceneKind s : {SceneKind::spring, SceneKind::projectile}) {
    for (Integrator i : all_integrators) {
      for (const char* p : precs) {
        const auto* e =
            c.find(fmt::format("engine/{}/{}/{}/{}", scene_name(s), p, integrator_name(i), big));
        const auto* t = c.find(fmt::format("triad/{}/{}", p, big));
        if (!e || !t) continue;
        line(fmt::format("| {} | `{}` | {} | {} | {} | {:.1f} | {:.1f} | {:.2f} |", scene_name(s),
                         integrator_name(i), p, e->bytes, si(double(big)), e->bandwidth(),
                         t->bandwidth(), e->bandwidth() / t->bandwidth()));
      }
    }
  }

  const std::int64_t peer_n = o.quick ? 10'000 : 100'000;
  line(fmt::format("\n#### Against Boost.Odeint (f64, N = {}, same answers checked first)\n",
                   si(double(peer_n))));
  line(
      "| system | Boost.Odeint | ns per body-step | fixstep | ns per body-step | fixstep speed-up "
      "|");
  line("|---|---|---|---|---|---|");
  auto peer = [&](const char* system, const char* ode, const std::string& ode_key, const char* ours,
                  const std::string& our_key) {
    const auto *a = c.find(ode_key), *b = c.find(our_key);
    if (!a || !b) return;
    line(fmt::format("| {} | `{}` | {:.3g} | `{}` | {:.3g} | {:.1f}x |", system, ode,
                     a->ns_per_body_step(), ours, b->ns_per_body_step(), a->ns / b->ns));
  };
  peer("undamped springs", "symplectic_euler",
       fmt::format("odeint/undamped/f64/symplectic_euler/{}", peer_n), "semi_implicit_euler",
       fmt::format("engine/undamped/f64/semi_implicit_euler/{}", peer_n));
  peer("damped springs", "runge_kutta4", fmt::format("odeint/spring/f64/runge_kutta4/{}", peer_n),
       "rk4", fmt::format("engine/spring/f64/rk4/{}", peer_n));

  if (!o.quick) {
    line("\n#### A damped f32 scene over time (1000 bodies, ζ = 1): 10^4 ticks timed\n");
    line("| flush subnormals | ticks 0 ... 10^4 | ticks 10^6 ... 10^6 + 10^4 | aged / fresh |");
    line("|---|---|---|---|");
    for (int flush : {1}) {
      const auto* fresh = c.find(fmt::format("aging/f32/flush:{}/from/0/{}", flush, flush));
      const auto* aged = c.find(fmt::format("aging/f32/flush:{}/from/1000000/{}", flush, flush));
      if (!fresh || !aged) continue;
      line(fmt::format("| {} | {:.2f} ms | {:.2f} ms | {:.2f} |", flush ? "on (default)" : "off",
                       fresh->ns * 1e-6, aged->ns * 1e-6, aged->ns / fresh->ns));
    }
  }

  // The targets, as medians of ratios measured in this run.
  line("\n#### Targets\n");
  line("| target | measured | met |");
  line("|---|---|---|");
  auto target = [&](const std::string& what, double v, double goal, const std::string& fmtd) {
    line(fmt::format(
        "| {} | {} | {} |", what, fmtd,
        v >= goal ? "yes" : fmt::format("**no** ({:.0f} % short)", 100.0 * (goal - v) / goal)));
  };
  {
    std::vector<double> ratios;
    double worst = 1e9;
    std::string worst_key;
    for (SceneKind s : {SceneKind::spring, SceneKind::projectile}) {
      for (Integrator i : all_integrators) {
        for (const char* p : precs) {
          for (auto n : ns) {
            if (n < 4096 || n > 1'000'000) continue;
            const auto key = fmt::format("{}/{}/{}/{}", scene_name(s), p, integrator_name(i), n);
            const auto *e = c.find("engine/" + key), *r = c.find("raw/" + key);
            if (!e || !r) continue;
            ratios.push_back(r->ns / e->ns);
            if (r->ns / e->ns < worst) worst = r->ns / e->ns, worst_key = key;
          }
        }
      }
    }
    if (!ratios.empty()) {
      std::sort(ratios.begin(), ratios.end());
      const double median = ratios[ratios.size() / 2];
      target(
          "engine ≥ 80 % of the raw fused loop, N = 4096 … 10^6 (median over scenes, "
          "integrators, precisions, N)",
          median, 0.8, fmt::format("{:.2f} (lowest {:.2f}: {})", median, worst, worst_key));
      target("… and the lowest single case", worst, 0.8, fmt::format("{:.2f}", worst));
    }
  }
  for (const char* p : precs) {
    const auto* e = c.find(fmt::format("engine/spring/{}/semi_implicit_euler/{}", p, big));
    const auto* t = c.find(fmt::format("triad/{}/{}", p, big));
    if (e && t) {
      target(fmt::format("engine ≥ 80 % of triad bandwidth at N = {} (spring, semi-implicit, {})",
                         si(double(big)), p),
             e->bandwidth() / t->bandwidth(), 0.8,
             fmt::format("{:.2f} ({:.1f} of {:.1f} GB/s)", e->bandwidth() / t->bandwidth(),
                         e->bandwidth(), t->bandwidth()));
    }
  }
  {
    const auto* a = c.find(fmt::format("odeint/undamped/f64/symplectic_euler/{}", peer_n));
    const auto* b = c.find(fmt::format("engine/undamped/f64/semi_implicit_euler/{}", peer_n));
    if (a && b)
      target("semi-implicit Euler ≥ 3x Boost.Odeint symplectic_euler", a->ns / b->ns, 3.0,
             fmt::format("{:.1f}x", a->ns / b->ns));
    const auto* c4 = c.find(fmt::format("odeint/spring/f64/runge_kutta4/{}", peer_n));
    const auto* e4 = c.find(fmt::format("engine/spring/f64/rk4/{}", peer_n));
    if (c4 && e4)
      target("RK4 ≥ 10x Boost.Odeint runge_kutta4", c4->ns / e4->ns, 10.0,
             fmt::format("{:.1f}x", c4->ns / e4->ns));
  }
  if (!o.quick) {
    const auto* fresh = c.find("aging/f32/flush:1/from/0/1");
    const auto* aged = c.find("aging/f32/flush:1/from/1000000/1");
    if (fresh && aged) {
      const double r = aged->ns / fresh->ns;
      line(fmt::format(
          "| damped f32 after 10^6 ticks within 1.2x of its first 10^4 | {:.2f}x | {} |", r,
          r <= 1.2 ? "yes" : "**no**"));
    }
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  std::vector<char*> args;
  for (int a = 0; a < argc; ++a) {
    if (std::strcmp(argv[a], "--quick") == 0)
      o.quick = true;
    else if (std::strcmp(argv[a], "--verify-only") == 0)
      o.verify_only = true;
    else if (std::strncmp(argv[a], "--report=", 9) == 0)
      o.report = argv[a] + 9;
    else if (std::strncmp(argv[a], "--simd=", 7) == 0) {
      const std::string_view want = argv[a] + 7;
      bool known = false;
      for (SimdLevel l : {SimdLevel::baseline, SimdLevel::avx2, SimdLevel::avx512}) {
        if (want == simd_level_name(l)) o.simd = l, known = true;
      }
      if (!known || !simd_supported(o.simd)) {
        std::fprintf(stderr,
                     "bench_throughput: --simd=%s: not one of baseline, avx2, avx512 "
                     "supported here\n",
                     argv[a] + 7);
        return 2;
      }
    } else
      args.push_back(argv[a]);
  }
  std::string levels;
  for (SimdLevel l : {SimdLevel::baseline, SimdLevel::avx2, SimdLevel::avx512}) {
    if (!simd_supported(l)) continue;
    levels += (levels.empty() ? "" : ", ") + std::string(simd_level_name(l));
    for (SceneKind s : {SceneKind::spring, SceneKind::projectile}) {
      for (Integrator i : all_integrators) verify_raw<float>(s, i, l), verify_raw<double>(s, i, l);
    }
  }
  set_simd_level(o.simd);
  verify_odeint();
  if (check_failures > 0) return 1;
  std::printf(
      "checks: at every SIMD level this CPU runs (%s), the engine and the raw loops "
      "reproduce the baseline raw loop bit for bit (12 integrator x precision cases per "
      "scene); Boost.Odeint agrees to 1e-11. Timing at level %s.\n",
      levels.c_str(), std::string(simd_level_name(o.simd)).c_str());
  if (o.verify_only) return 0;

  int bargc = static_cast<int>(args.size());
  benchmark::Initialize(&bargc, args.data());
  if (benchmark::ReportUnrecognizedArguments(bargc, args.data())) return 1;
  register_all(o);
  Collector collector;
  benchmark::RunSpecifiedBenchmarks(&collector);
  benchmark::Shutdown();
  const std::string md = report(collector, o);
  std::fputs(md.c_str(), stdout);
  if (o.report) {
    try {
      write_file_atomic(*o.report, md);
    } catch (const CaptureError& e) {
      std::fprintf(stderr, "bench_throughput: %s\n", e.what());
      return 1;
    }
  }
  return 0;
}
