// World stepping: force evaluation and the integrators (see integrators.hpp for the formulas,
// orders, stability bounds and sources of each).
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "fixstep/simd.hpp"
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


}  // namespace

// --- the force field of one body and the fused sweep over all bodies ---------------------

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
  Real decay[Decays > 0 ? Decays : 1]{};

  /// a_c(x): the conservative part (spring, constant force, gravity, push), m/s². The push
  /// is folded into c when the sweep loads it (Accel is on whenever the push is non-zero).
  [[gnu::always_inline]] void conservative(Real x, Real y, Real& ax, Real& ay) const {
    if constexpr (S == SpringShape::none) {
      if constexpr (Accel) ax = cx, ay = cy;
      else ax = Real(0), ay = Real(0);
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

/// Runs step(x, y, vx, vy, field) on every body: one pass, each body's state loaded and stored
/// once, each declared coefficient read once. The restrict-qualified parameters promise the
/// compiler that the arrays do not overlap, so it can vectorize the loop (see the -O3 note in
/// engine/CMakeLists.txt). Pointers of parts the Field leaves out may be null. Inlined into
/// one function per SimdLevel (below), which the compiler vectorizes for that level.
#define FIXSTEP_SWEEP_PARAMS                                                                   \
  std::size_t n, Real *__restrict x, Real *__restrict y, Real *__restrict vx,                  \
      Real *__restrict vy, const Real *__restrict k, const Real *__restrict anchor_x,          \
      const Real *__restrict anchor_y, const Real *__restrict rest,                            \
      const Real *__restrict gamma, const Real *__restrict cx, const Real *__restrict cy,      \
      const Real *__restrict decay0, const Real *__restrict decay1, const Real push[2], Step step
#define FIXSTEP_SWEEP_ARGS \
  n, x, y, vx, vy, k, anchor_x, anchor_y, rest, gamma, cx, cy, decay0, decay1, push, step

/// Returns true if some body's new state is out of range (NaN, ±inf or beyond
/// max_state_magnitude): the runtime guard, an OR of compares on values still in registers.
template <class Field, class Real, class Step>
[[gnu::always_inline]] inline bool sweep_loop(FIXSTEP_SWEEP_PARAMS) {
  const Real push_x = push[0], push_y = push[1];
  const Real limit = static_cast<Real>(max_state_magnitude);
  // A conditional reduction in Real (GCC vectorizes this select at every level; an integer
  // OR of the compares is not vectorized for doubles on SSE2).
  Real out_of_range = 0;
  for (std::size_t j = 0; j < n; ++j) {
    Field f;
    if constexpr (Field::shape != SpringShape::none) {
      f.k = k[j], f.anchor_x = anchor_x[j], f.anchor_y = anchor_y[j];
    }
    if constexpr (Field::shape == SpringShape::rest_length) f.rest = rest[j];
    if constexpr (Field::damped && Field::decays == 0) f.gamma = gamma[j];
    if constexpr (Field::damped && Field::decays >= 1) f.decay[0] = decay0[j];
    if constexpr (Field::damped && Field::decays >= 2) f.decay[1] = decay1[j];
    if constexpr (Field::accel) f.cx = cx[j] + push_x, f.cy = cy[j] + push_y;
    Real X = x[j], Y = y[j], VX = vx[j], VY = vy[j];
    step(X, Y, VX, VY, f);
    x[j] = X, y[j] = Y, vx[j] = VX, vy[j] = VY;
    // !(|v| <= limit) is true for NaN too (every comparison with NaN is false).
    // int & int, not &&: no branch in the loop body (it would stop the vectorizer).
    const bool in_range = (int(std::abs(X) <= limit) & int(std::abs(Y) <= limit) &
                           int(std::abs(VX) <= limit) & int(std::abs(VY) <= limit)) != 0;
    out_of_range = in_range ? out_of_range : Real(1);
  }
  return out_of_range != Real(0);
}

// The same loop compiled for each SimdLevel (fixstep/simd.hpp). These templates have internal
// linkage (anonymous namespace) and inline everything they call that is marked always_inline,
// so no code compiled for a wider ISA can be picked by the linker for a baseline caller.
template <class Field, class Real, class Step>
[[gnu::noinline]] bool sweep_baseline(FIXSTEP_SWEEP_PARAMS) {
  return sweep_loop<Field>(FIXSTEP_SWEEP_ARGS);
}
#if FIXSTEP_HAS_SIMD_CLONES
template <class Field, class Real, class Step>
FIXSTEP_TARGET_AVX2 bool sweep_avx2(FIXSTEP_SWEEP_PARAMS) {
  return sweep_loop<Field>(FIXSTEP_SWEEP_ARGS);
}
template <class Field, class Real, class Step>
FIXSTEP_TARGET_AVX512 bool sweep_avx512(FIXSTEP_SWEEP_PARAMS) {
  return sweep_loop<Field>(FIXSTEP_SWEEP_ARGS);
}
#endif

/// The sweep at the level in use (simd_level(); chosen once per tick, not per body). Returns
/// true if some body's state went out of range.
template <class Field, class Real, class Step>
bool sweep(SimdLevel level, FIXSTEP_SWEEP_PARAMS) {
#if FIXSTEP_HAS_SIMD_CLONES
  if (level == SimdLevel::avx512) return sweep_avx512<Field>(FIXSTEP_SWEEP_ARGS);
  if (level == SimdLevel::avx2) return sweep_avx2<Field>(FIXSTEP_SWEEP_ARGS);
#endif
  (void)level;
  return sweep_baseline<Field>(FIXSTEP_SWEEP_ARGS);
}
#undef FIXSTEP_SWEEP_PARAMS
#undef FIXSTEP_SWEEP_ARGS

/// Calls visit(field) with a default BodyField whose compile-time parts match the world's
/// flags: 3 spring shapes x damped or not x constant acceleration or not.
template <class Real, int Decays, class Visit>
void with_field(SpringShape shape, bool damped, bool accel, Visit&& visit) {
  auto pick_accel = [&]<SpringShape S, bool D>() {
    if (accel) visit(BodyField<Real, S, D, true, Decays>{});
    else visit(BodyField<Real, S, D, false, Decays>{});
  };
  auto pick_damped = [&]<SpringShape S>() {
    if (damped) pick_accel.template operator()<S, true>();
    else pick_accel.template operator()<S, false>();
  };
  switch (shape) {
    case SpringShape::none: pick_damped.template operator()<SpringShape::none>(); break;
    case SpringShape::linear: pick_damped.template operator()<SpringShape::linear>(); break;
    case SpringShape::rest_length:
      pick_damped.template operator()<SpringShape::rest_length>();
      break;
  }
}

/// Velocity Verlet (kick-drift-kick) on a_c, between two halves of the exact damping flow with
/// factor `decay` = e^{-γh/2}: S(h) = D(h/2) ∘ VV(h) ∘ D(h/2) (Strang). Symmetric, so second
/// order, and a valid base for the triple jump.
template <class Field, class Real>
[[gnu::always_inline]] inline void strang_verlet(Real& x, Real& y, Real& vx, Real& vy, const Field& f, Real h,
                          Real decay) {
  const Real half = h * Real(0.5);
  Real ax, ay;
  if constexpr (Field::damped) vx *= decay, vy *= decay;
  f.conservative(x, y, ax, ay);
  vx += ax * half, vy += ay * half;  // kick h/2
  x += vx * h, y += vy * h;          // drift h
  f.conservative(x, y, ax, ay);
  vx += ax * half, vy += ay * half;  // kick h/2
  if constexpr (Field::damped) vx *= decay, vy *= decay;
}

// Backward Euler for one body (fixstep's forces never couple bodies). With r = x_{n+1} the
// equations reduce to R(r) = (1 + hγ)(r - x) - h v - h² a_c(r) = 0, v_{n+1} = (r - x)/h.
template <class Field, class Real>
[[gnu::always_inline]] inline void implicit_euler(Real& x, Real& y, Real& vx, Real& vy, const Field& f, Real h) {
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
      if (std::abs(step_x) + std::abs(step_y) <= Real(4) * std::numeric_limits<Real>::epsilon() * scale) break;
    }
    vx = (rx - x) / h, vy = (ry - y) / h;
    x = rx, y = ry;
  }
}

}  // namespace

template <class Real>
void World<Real>::accelerations(std::span<Real> ax, std::span<Real> ay, const TickInput& input) {
  if (ax.size() < body_count() || ay.size() < body_count()) {
    throw std::invalid_argument("World::accelerations: output spans are shorter than body_count()");
  }
  if (terms_dirty_) rebuild_terms();
  const Coefficients& c = coeff_;
  for (std::size_t j = 0; j < body_count(); ++j) {
    BodyField<Real, SpringShape::rest_length, true, true, 0> f;
    f.k = c.stiffness[j], f.anchor_x = c.anchor_x[j], f.anchor_y = c.anchor_y[j];
    f.rest = c.rest[j], f.gamma = c.gamma[j];
    f.cx = c.accel_x[j] + static_cast<Real>(input.push.x);
    f.cy = c.accel_y[j] + static_cast<Real>(input.push.y);
    f.full(x_[j], y_[j], vx_[j], vy_[j], ax[j], ay[j]);
  }
}

// The damping-flow factors e^{-γτ} of every body (1 where γ = 0), computed in double once per
// τ and cached: a tick of Verlet needs one τ, of Forest–Ruth two.
template <class Real>
const Real* World<Real>::damping_decay(double tau) {
  auto flow = std::find_if(flows_.begin(), flows_.end(),
                           [tau](const DampingFlow& f) { return f.tau == tau; });
  if (flow == flows_.end()) {
    if (flows_.size() >= 4) flows_.clear();  // the step sizes changed
    DampingFlow f;
    f.tau = tau;
    f.decay.resize(coeff_.gamma.size());
    for (std::size_t j = 0; j < f.decay.size(); ++j) {
      f.decay[j] = static_cast<Real>(std::exp(-double(coeff_.gamma[j]) * tau));
    }
    flows_.push_back(std::move(f));
    flow = flows_.end() - 1;
  }
  return flow->decay.data();
}

template <class Real>
std::size_t World<Real>::bytes_per_body_step() {
  if (terms_dirty_) rebuild_terms();
  const Coefficients& c = coeff_;
  std::size_t arrays = 8;  // x, y, vx, vy: read and written
  if (c.spring) arrays += c.rest_length ? 4 : 3;
  if (c.damping) arrays += settings_.integrator == Integrator::forest_ruth ? 2 : 1;
  if (c.accel) arrays += 2;
  arrays *= static_cast<std::size_t>(settings_.substeps);
  if (keep_previous_) arrays += 4;
  return arrays * sizeof(Real);
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
  const Real h = static_cast<Real>(settings_.dt / settings_.substeps);
  const Coefficients& c = coeff_;
  const SpringShape shape = !c.spring        ? SpringShape::none
                            : c.rest_length ? SpringShape::rest_length
                                            : SpringShape::linear;
  const std::size_t n = x_.size();
  const bool accel = c.accel || push[0] != Real(0) || push[1] != Real(0);
  // Every sweep gets the same arrays; each Field reads only its own.
  const SimdLevel level = simd_level();
  bool out_of_range = false;
  auto run = [&](auto field, const Real* decay0, const Real* decay1, auto body_step) {
    out_of_range |= sweep<decltype(field)>(level, n, x_.data(), y_.data(), vx_.data(), vy_.data(), c.stiffness.data(),
                           c.anchor_x.data(), c.anchor_y.data(), c.rest.data(), c.gamma.data(),
                           c.accel_x.data(), c.accel_y.data(), decay0, decay1, push, body_step);
  };

  for (int s = 0; s < settings_.substeps; ++s) {
    switch (settings_.integrator) {
      case Integrator::semi_implicit_euler:
        with_field<Real, 0>(shape, c.damping, accel, [&](auto field) {
          run(field, nullptr, nullptr, [h](Real& x, Real& y, Real& vx, Real& vy, const auto& f) {
            Real ax, ay;
            f.full(x, y, vx, vy, ax, ay);
            vx += ax * h, vy += ay * h;  // v_{n+1} = v_n + a_n h
            x += vx * h, y += vy * h;    // x_{n+1} = x_n + v_{n+1} h
          });
        });
        break;
      case Integrator::explicit_euler:
        with_field<Real, 0>(shape, c.damping, accel, [&](auto field) {
          run(field, nullptr, nullptr, [h](Real& x, Real& y, Real& vx, Real& vy, const auto& f) {
            Real ax, ay;
            f.full(x, y, vx, vy, ax, ay);
            x += vx * h, y += vy * h;    // x_{n+1} = x_n + v_n h
            vx += ax * h, vy += ay * h;  // v_{n+1} = v_n + a_n h
          });
        });
        break;
      case Integrator::velocity_verlet: {
        const Real* d = c.damping ? damping_decay(0.5 * double(h)) : nullptr;
        with_field<Real, 1>(shape, c.damping, accel, [&](auto field) {
          run(field, d, nullptr, [h](Real& x, Real& y, Real& vx, Real& vy, const auto& f) {
            strang_verlet(x, y, vx, vy, f, h, f.decay[0]);
          });
        });
        break;
      }
      case Integrator::forest_ruth: {
        const Real h1 = static_cast<Real>(forest_ruth_w1 * double(h));
        const Real h0 = static_cast<Real>(forest_ruth_w0 * double(h));
        const Real* d1 = c.damping ? damping_decay(0.5 * double(h1)) : nullptr;
        const Real* d0 = c.damping ? damping_decay(0.5 * double(h0)) : nullptr;
        with_field<Real, 2>(shape, c.damping, accel, [&](auto field) {
          run(field, d1, d0, [h1, h0](Real& x, Real& y, Real& vx, Real& vy, const auto& f) {
            strang_verlet(x, y, vx, vy, f, h1, f.decay[0]);
            strang_verlet(x, y, vx, vy, f, h0, f.decay[1]);
            strang_verlet(x, y, vx, vy, f, h1, f.decay[0]);
          });
        });
        break;
      }
      case Integrator::rk4:
        with_field<Real, 0>(shape, c.damping, accel, [&](auto field) {
          run(field, nullptr, nullptr, [h](Real& x, Real& y, Real& vx, Real& vy, const auto& f) {
            // y = (x, v), f(y) = (v, a(x, v)); d accumulates k1 + 2 k2 + 2 k3, s is the stage.
            const Real half = h * Real(0.5);
            Real ax, ay;
            f.full(x, y, vx, vy, ax, ay);  // k1
            Real dx = vx, dy = vy, dvx = ax, dvy = ay;
            Real sx = x + half * vx, sy = y + half * vy;
            Real svx = vx + half * ax, svy = vy + half * ay;
            f.full(sx, sy, svx, svy, ax, ay);  // k2 at y + h k1 / 2
            dx += Real(2) * svx, dy += Real(2) * svy;
            dvx += Real(2) * ax, dvy += Real(2) * ay;
            sx = x + half * svx, sy = y + half * svy;
            svx = vx + half * ax, svy = vy + half * ay;
            f.full(sx, sy, svx, svy, ax, ay);  // k3 at y + h k2 / 2
            dx += Real(2) * svx, dy += Real(2) * svy;
            dvx += Real(2) * ax, dvy += Real(2) * ay;
            sx = x + h * svx, sy = y + h * svy;
            svx = vx + h * ax, svy = vy + h * ay;
            f.full(sx, sy, svx, svy, ax, ay);  // k4 at y + h k3
            const Real sixth = h / Real(6);
            x += sixth * (dx + svx), y += sixth * (dy + svy);
            vx += sixth * (dvx + ax), vy += sixth * (dvy + ay);
          });
        });
        break;
      case Integrator::implicit_euler:
        with_field<Real, 0>(shape, c.damping, accel, [&](auto field) {
          run(field, nullptr, nullptr, [h](Real& x, Real& y, Real& vx, Real& vy, const auto& f) {
            implicit_euler(x, y, vx, vy, f, h);
          });
        });
        break;
    }
  }
  ++tick_;
  if (out_of_range && !fault_) record_fault();
}

// Cold path: find the first body (dense order) and component out of range after this tick.
template <class Real>
void World<Real>::record_fault() {
  const std::span<const Real> fields[] = {x_, y_, vx_, vy_};
  const char* names[] = {"x", "y", "vx", "vy"};
  for (std::size_t j = 0; j < x_.size(); ++j) {
    for (int f = 0; f < 4; ++f) {
      const double v = static_cast<double>(fields[f][j]);
      if (!(std::abs(v) <= max_state_magnitude)) {
        fault_ = StateFault{.index = j, .name = names_[j], .tick = tick_, .time = time(),
                            .field = names[f], .value = v};
        return;
      }
    }
  }
}

// world.hpp declares `extern template class World<Real>`, so every member defined in this
// file is instantiated here explicitly.
#define FIXSTEP_INSTANTIATE(Real)                                                               \
  template void World<Real>::step(const TickInput&);                                            \
  template void World<Real>::accelerations(std::span<Real>, std::span<Real>, const TickInput&); \
  template std::size_t World<Real>::bytes_per_body_step();                                      \
  template void World<Real>::record_fault();                                                    \
  template const Real* World<Real>::damping_decay(double);
FIXSTEP_INSTANTIATE(float)
FIXSTEP_INSTANTIATE(double)
#undef FIXSTEP_INSTANTIATE

}  // namespace fixstep
