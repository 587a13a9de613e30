// World stepping: force evaluation and the integrators (see integrators.hpp for the formulas,
// orders, stability bounds and sources of each).
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "body_field.hpp"
#include "disc_contacts.hpp"
#include "fixstep/core/components.hpp"
#include "fixstep/core/det_math.hpp"
#include "fixstep/core/float_mode.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/simd.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/stop_request.hpp"
#include "phase_clock.hpp"
#include "simd_targets.hpp"
#include "world_kernel.hpp"

namespace fixstep {

// --- the fused sweep over all bodies ---------------------------------------------------------

namespace {

/// What the fused sweep reads and writes, by pointer: the bodies' state (m, m/s), the field's
/// coefficient arrays (World::Coefficients; BodyField names their units), the damping decay
/// factors of velocity Verlet and Forest–Ruth, and the tick's push (m/s²). The pointers are
/// restrict-qualified members of a struct taken by value, which GCC honours as it does restrict
/// parameters: the arrays do not overlap, so it can vectorize the loop (see the -O3 note in
/// engine/CMakeLists.txt). Pointers of parts the Field leaves out may be null.
template <class Real>
struct SweepArrays {
  std::size_t n;
  Real* __restrict x, * __restrict y, * __restrict vx, * __restrict vy;
  const Real* __restrict k, * __restrict anchor_x, * __restrict anchor_y, * __restrict rest;
  const Real* __restrict gamma, * __restrict cx, * __restrict cy;
  const Real* __restrict decay0, * __restrict decay1;
  Real push_x, push_y;
  /// Every body's γ is gamma_value (Coefficients::gamma_uniform): the sweep takes it as one
  /// value instead of loading it per body (the same values, so the same bits).
  bool gamma_uniform;
  Real gamma_value;
};

/// Runs step(x, y, vx, vy, field) on every body: one pass, each body's state loaded and stored
/// once, each declared coefficient read once. Inlined into one function per SimdLevel (below),
/// which the compiler vectorizes for that level. Returns true if some body's new state is out
/// of range (NaN, ±inf or beyond max_state_magnitude): the runtime guard, an OR of compares on
/// values still in registers. UniformGamma: every body's γ is a.gamma_value, not loaded.
template <class Field, bool UniformGamma, class Real, class Step>
[[gnu::always_inline]] inline bool sweep_bodies(SweepArrays<Real> a, Step step) {
  Real* __restrict x = a.x, * __restrict y = a.y, * __restrict vx = a.vx, * __restrict vy = a.vy;
  const Real limit = static_cast<Real>(max_state_magnitude);
  // A conditional reduction in Real (GCC vectorizes this select at every level; an integer
  // OR of the compares is not vectorized for doubles on SSE2).
  Real out_of_range = 0;
  for (std::size_t j = 0; j < a.n; ++j) {
    Field f;
    if constexpr (Field::shape != SpringShape::none) {
      f.k = a.k[j], f.anchor_x = a.anchor_x[j], f.anchor_y = a.anchor_y[j];
    }
    if constexpr (Field::shape == SpringShape::rest_length) f.rest = a.rest[j];
    if constexpr (Field::damped && Field::decays == 0)
      f.gamma = UniformGamma ? a.gamma_value : a.gamma[j];
    if constexpr (Field::damped && Field::decays >= 1) f.decay[0] = a.decay0[j];
    if constexpr (Field::damped && Field::decays >= 2) f.decay[1] = a.decay1[j];
    if constexpr (Field::accel) f.cx = a.cx[j] + a.push_x, f.cy = a.cy[j] + a.push_y;
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

/// sweep_bodies(), with a uniform γ as one value when the field reads γ (a loop of its own: a
/// choice within the loop stops the vectorizer).
template <class Field, class Real, class Step>
[[gnu::always_inline]] inline bool sweep_loop(SweepArrays<Real> a, Step step) {
  if constexpr (Field::damped && Field::decays == 0) {
    if (a.gamma_uniform) return sweep_bodies<Field, true>(a, step);
  }
  return sweep_bodies<Field, false>(a, step);
}

// The same loop compiled for each SimdLevel (fixstep/core/simd.hpp). These templates have internal
// linkage (anonymous namespace) and inline everything they call that is marked always_inline,
// so no code compiled for a wider ISA can be picked by the linker for a baseline caller.
template <class Field, class Real, class Step>
[[gnu::noinline]] bool sweep_baseline(SweepArrays<Real> a, Step step) {
  return sweep_loop<Field>(a, step);
}
#if FIXSTEP_HAS_SIMD_CLONES
template <class Field, class Real, class Step>
FIXSTEP_TARGET_AVX2 bool sweep_avx2(SweepArrays<Real> a, Step step) {
  return sweep_loop<Field>(a, step);
}
template <class Field, class Real, class Step>
FIXSTEP_TARGET_AVX512 bool sweep_avx512(SweepArrays<Real> a, Step step) {
  return sweep_loop<Field>(a, step);
}
#endif

/// The sweep at the level in use (simd_level(); chosen once per tick, not per body). Returns
/// true if some body's state went out of range.
template <class Field, class Real, class Step>
bool sweep(SimdLevel level, SweepArrays<Real> a, Step step) {
#if FIXSTEP_HAS_SIMD_CLONES
  if (level == SimdLevel::avx512) return sweep_avx512<Field>(a, step);
  if (level == SimdLevel::avx2) return sweep_avx2<Field>(a, step);
#endif
  (void)level;
  return sweep_baseline<Field>(a, step);
}

/// Sets every value of v below `below` in magnitude to zero of its sign: the software flush of
/// WorldSettings::flush_denormals. Plain compares and copies, so the same on every platform and
/// FPU mode; vectorized (compare and blend) at -O3.
template <class Real>
void flush_below_to_zero(std::vector<Real>& v, Real below) {
  for (Real& e : v) e = flush_tiny(e, below);
}

}  // namespace

template <class Real>
void detail::WorldKernel<Real>::accelerations(std::span<Real> ax, std::span<Real> ay,
                                              const TickInput& input) {
  if (ax.size() < body_count() || ay.size() < body_count()) {
    throw std::invalid_argument("World::accelerations: output spans are shorter than body_count()");
  }
  const IeeeFloatMode ieee;  // its results, and the coefficients it may rebuild (float_mode.hpp)
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
  // Links (cold path, for tests and tools; the step's passes are in world_coupled.cpp).
  for (const LinkDef& l : link_defs_) {
    const std::size_t a = bodies_.index(l.body_a), b = bodies_.index(l.body_b);
    const double dx = double(x_[a]) - double(x_[b]), dy = double(y_[a]) - double(y_[b]);
    const double ux = double(vx_[a]) - double(vx_[b]), uy = double(vy_[a]) - double(vy_[b]);
    const LinkSpring& s = l.spring;
    double fx = -s.stiffness * dx - s.damping * ux, fy = -s.stiffness * dy - s.damping * uy;
    if (s.rest_length != 0.0) {
      const double len = std::sqrt(dx * dx + dy * dy);
      const double nx = len > 0.0 ? dx / len : 0.0, ny = len > 0.0 ? dy / len : 0.0;
      const double t = len > 0.0 ? s.stiffness * (len - s.rest_length) : 0.0;
      const double un = ux * nx + uy * ny;
      fx = -t * nx - s.damping * un * nx, fy = -t * ny - s.damping * un * ny;
    }
    ax[a] += static_cast<Real>(fx / mass_[a]), ay[a] += static_cast<Real>(fy / mass_[a]);
    ax[b] -= static_cast<Real>(fx / mass_[b]), ay[b] -= static_cast<Real>(fy / mass_[b]);
  }
}

// The damping-flow factors e^{-γτ} of every body (1 where γ = 0), computed in double once per
// τ and cached: a tick of Verlet needs one τ, of Forest–Ruth two.
template <class Real>
const Real* detail::WorldKernel<Real>::damping_decay(double tau) {
  auto flow = std::find_if(flows_.begin(), flows_.end(),
                           [tau](const DampingFlow& f) { return f.tau == tau; });
  if (flow == flows_.end()) {
    if (flows_.size() >= 4) flows_.clear();  // the step sizes changed
    DampingFlow f;
    f.tau = tau;
    f.decay.resize(coeff_.gamma.size());
    for (std::size_t j = 0; j < f.decay.size(); ++j) {
      f.decay[j] = static_cast<Real>(det::exp(-double(coeff_.gamma[j]) * tau));
    }
    flows_.push_back(std::move(f));
    flow = flows_.end() - 1;
  }
  return flow->decay.data();
}

template <class Real>
std::size_t detail::WorldKernel<Real>::bytes_per_body_step() {
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
void detail::WorldKernel<Real>::apply_drag(const TickInput& input) {
  // The drag spring a = -ω²(x - p) - 2ζω v per unit mass, taken implicitly over the tick
  // (v1 = v0 + h a(x0 + h v1, v1)), so it is stable at any dt and any integrator:
  //   v1 = (v0 - h ω² (x0 - p)) / (1 + 2ζω h + ω² h²).
  // The integrator then steps the body with v1 and its own forces (first-order splitting).
  constexpr double two_pi = 6.283185307179586;
  const double w = two_pi * drag_frequency, h = settings_.dt;
  const double denominator = 1.0 + 2.0 * drag_damping_ratio * w * h + w * w * h * h;
  const std::size_t j = bodies_.index(input.drag_body);
  const double vx = (double(vx_[j]) - h * w * w * (double(x_[j]) - input.pointer.x)) / denominator;
  const double vy = (double(vy_[j]) - h * w * w * (double(y_[j]) - input.pointer.y)) / denominator;
  if (std::isfinite(vx) && std::isfinite(vy))
    vx_[j] = static_cast<Real>(vx), vy_[j] = static_cast<Real>(vy);
}

template <class Real>
void detail::WorldKernel<Real>::keep_previous_positions() {
  if (awake_.skip()) {  // a sleeper's previous position is where it sleeps (awake_runs.hpp)
    for (const IndexRun& r : awake_.bodies) {
      std::copy(x_.begin() + r.begin, x_.begin() + r.end, prev_x_.begin() + r.begin);
      std::copy(y_.begin() + r.begin, y_.begin() + r.end, prev_y_.begin() + r.begin);
    }
    return;
  }
  std::copy(x_.begin(), x_.end(), prev_x_.begin());
  std::copy(y_.begin(), y_.end(), prev_y_.begin());
}

// Every flush_denormals_every ticks: a separate pass over the four state arrays costs as much
// memory traffic as a tick of the fused sweep, so it runs once in 64 ticks. A damped world
// (bodies or links) decays towards zero: its values below flush_below (body_field.hpp) become 0,
// far above the subnormals, so that until the next flush every value of it is either 0 or (a
// sum of values at least that large, rounded) at least 2^-24 of a value that large, less what
// 64 ticks of damping take; its products with the tick's coefficients then stay normal while
// that decay is below 2^27 and the coefficients above 2^-20 (docs/INTEGRATORS.md). Other
// worlds, which do not decay, flush only what is subnormal.
template <class Real>
void detail::WorldKernel<Real>::flush_state_subnormals() {
  if (!settings_.flush_denormals || tick_ % flush_denormals_every != 0) return;
  const Real below =
      coeff_.damping || net_.damped ? flush_below<Real> : std::numeric_limits<Real>::min();
  for (std::vector<Real>* v : {&x_, &y_, &vx_, &vy_}) flush_below_to_zero(*v, below);
}

template <class Real>
void detail::WorldKernel<Real>::integrate(const TickInput& input) {
  if (!fused_step()) {  // with the account only, the sleepers skipped too (awake_runs.hpp)
    stepped_ = awake_.on ? count_in_runs(awake_.bodies) : x_.size();
    step_multipass(input);  // links or the dissipation account: world_coupled.cpp
    return;
  }
  threads_used_ = 1;
  const Real push[2] = {static_cast<Real>(input.push.x), static_cast<Real>(input.push.y)};
  const Real h = static_cast<Real>(settings_.dt / settings_.substeps);
  const Coefficients& c = coeff_;
  const SpringShape shape = !c.spring       ? SpringShape::none
                            : c.rest_length ? SpringShape::rest_length
                                            : SpringShape::linear;
  const std::size_t n = x_.size();
  const bool accel = c.accel || push[0] != Real(0) || push[1] != Real(0);
  // Every sweep gets the same arrays; each Field reads only its own.
  const SimdLevel level = simd_level();
  bool out_of_range = false;
  // The arrays from the run's first body on, for its bodies (null pointers stay null).
  auto from = [](SweepArrays<Real> a, IndexRun r) {
    auto at = [&](auto* p) { return p != nullptr ? p + r.begin : p; };
    a.n = r.end - r.begin;
    a.x = at(a.x), a.y = at(a.y), a.vx = at(a.vx), a.vy = at(a.vy);
    a.k = at(a.k), a.anchor_x = at(a.anchor_x), a.anchor_y = at(a.anchor_y), a.rest = at(a.rest);
    a.gamma = at(a.gamma), a.cx = at(a.cx), a.cy = at(a.cy);
    a.decay0 = at(a.decay0), a.decay1 = at(a.decay1);
    return a;
  };
  stepped_ = awake_.on ? count_in_runs(awake_.bodies) : n;
  auto run = [&](auto field, const Real* decay0, const Real* decay1, auto step_fn) {
    const SweepArrays<Real> arrays{.n = n,
                                   .x = x_.data(),
                                   .y = y_.data(),
                                   .vx = vx_.data(),
                                   .vy = vy_.data(),
                                   .k = c.stiffness.data(),
                                   .anchor_x = c.anchor_x.data(),
                                   .anchor_y = c.anchor_y.data(),
                                   .rest = c.rest.data(),
                                   .gamma = c.gamma.data(),
                                   .cx = c.accel_x.data(),
                                   .cy = c.accel_y.data(),
                                   .decay0 = decay0,
                                   .decay1 = decay1,
                                   .push_x = push[0],
                                   .push_y = push[1],
                                   .gamma_uniform = c.gamma_uniform,
                                   .gamma_value = c.gamma.empty() ? Real(0) : c.gamma[0]};
    if (!awake_.on) {
      out_of_range |= sweep<decltype(field)>(level, arrays, step_fn);
      return;
    }
    for (const IndexRun& r : awake_.bodies) {  // sleepers are not stepped (awake_runs.hpp)
      out_of_range |= sweep<decltype(field)>(level, from(arrays, r), step_fn);
    }
  };

  StepSizes<Real> sizes{h, static_cast<Real>(forest_ruth_w1 * double(h)),
                        static_cast<Real>(forest_ruth_w0 * double(h))};
  // Calls run() with the body step of integrator I (untracked: the fused pass keeps no
  // dissipation account; see step_multipass).
  auto integrate = [&]<Integrator I, int Decays>(const Real* decay0, const Real* decay1) {
    with_field<Real, Decays>(shape, c.damping, accel, [&](auto field) {
      run(field, decay0, decay1, [sizes](Real& x, Real& y, Real& vx, Real& vy, const auto& f) {
        Real unused = 0;
        body_step<I, false>(x, y, vx, vy, f, sizes, unused);
      });
    });
  };
  for (int s = 0; s < settings_.substeps; ++s) {
    throw_if_stop_requested();  // one relaxed load per substep (stop_request.hpp)
    const bool verlet = settings_.integrator == Integrator::velocity_verlet;
    const bool fr = settings_.integrator == Integrator::forest_ruth;
    dispatch(settings_.integrator, c.damping && verlet ? damping_decay(0.5 * double(h)) : nullptr,
             c.damping && fr ? damping_decay(0.5 * double(sizes.h1)) : nullptr,
             c.damping && fr ? damping_decay(0.5 * double(sizes.h0)) : nullptr, integrate);
  }
  ++tick_;
  if (out_of_range && !fault_) record_fault();
}

// Cold path: find the first body (dense order) and field out of range after this tick: its
// x, y, vx, vy; with rolling discs, or shapes, its angle and angular velocity; with the energy
// account its dissipated energy (finite), then each link's (named by its first body).
template <class Real>
void detail::WorldKernel<Real>::record_fault() {
  auto fault_at = [&](std::size_t j, const char* field, double v) {
    fault_ = StateFault{.body = bodies_.dense[j],
                        .name = names_[j],
                        .tick = tick_,
                        .time = time(),
                        .field = field,
                        .value = v,
                        .cap = {},
                        .with = {}};
  };
  const std::span<const Real> fields[] = {x_, y_, vx_, vy_, angle_, spin_};
  const char* names[] = {"x", "y", "vx", "vy", "angle", "angular_velocity"};
  const int count = rolling_ ? 6 : 4;
  for (std::size_t j = 0; j < x_.size(); ++j) {
    for (int f = 0; f < count; ++f) {
      const double v = static_cast<double>(fields[f][j]);
      if (!(std::abs(v) <= max_state_magnitude)) {
        fault_at(j, names[f], v);
        return;
      }
    }
    if (!shape_sets_.data.empty() && shape_sets_.set.contains(bodies_.dense[j])) {
      const ShapeSet& s = shape_sets_.data[shape_sets_.set.index(bodies_.dense[j])];
      if (!(std::abs(s.angle) <= max_state_magnitude)) return fault_at(j, "angle", s.angle);
      if (!(std::abs(s.spin) <= max_state_magnitude)) {
        return fault_at(j, "angular_velocity", s.spin);
      }
    }
    if (!std::isfinite(dissipated_body_[j])) {
      fault_at(j, "dissipated", double(dissipated_body_[j]));
      return;
    }
  }
  for (std::size_t i = 0; i < dissipated_link_.size(); ++i) {
    if (!std::isfinite(dissipated_link_[i])) {
      fault_at(bodies_.index(link_defs_[i].body_a), "dissipated", double(dissipated_link_[i]));
      return;
    }
  }
}

// The energy account's terms: a dissipated energy that is no longer finite is a fault (the
// balance E + E_dissipated - E0 would read NaN). One pass over the accounts a tick, only when
// they are kept.
template <class Real>
void detail::WorldKernel<Real>::check_energy_account() {
  if (!settings_.track_dissipation || fault_) return;
  bool bad = false;
  if (awake_.on) {  // a sleeper's account has not changed since it was checked
    for_each_in_runs(awake_.bodies,
                     [&](std::uint32_t j) { bad = bad || !std::isfinite(dissipated_body_[j]); });
  } else {
    for (const Real d : dissipated_body_) bad = bad || !std::isfinite(d);
  }
  for (const Real d : dissipated_link_) bad = bad || !std::isfinite(d);
  if (bad) record_fault();
}

// Cold path: a contact cap (limits.hpp) stopped part of this tick's contact work.
template <class Real>
void detail::WorldKernel<Real>::record_cap_fault(std::size_t body, const char* cap,
                                                 std::uint64_t limit, const std::string& with) {
  fault_ = StateFault{.body = bodies_.dense[body],
                      .name = names_[body],
                      .tick = tick_,
                      .time = time(),
                      .field = "contacts",
                      .value = static_cast<double>(limit),
                      .cap = cap,
                      .with = with};
}

}  // namespace fixstep
