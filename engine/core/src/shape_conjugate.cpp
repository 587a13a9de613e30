// The shape contacts' velocity sweeps, accelerated: the conjugate step after each sweep
// (sweep_conjugate.hpp says what it is and why the velocities may follow the impulses body by
// body). Every value's step is element-wise arithmetic, the same for a lane and a scalar, so the
// bits do not depend on the vector width, on whether the manifolds go through the lanes, or on
// how the passes are split between two threads. The lanes' pass is compiled for each SimdLevel
// (as shape_sweep.cpp's sweeps are).
#include <atomic>
#include <cstddef>
#include <tuple>
#include <vector>

#include "fixstep/core/simd.hpp"
#include "shape_world.hpp"
#include "simd_targets.hpp"

namespace fixstep::detail {

namespace {
std::atomic<bool> conjugate_on{true};
}  // namespace

void set_sweeps_conjugate(bool on) {
  conjugate_on.store(on, std::memory_order_relaxed);
}

bool sweeps_conjugate() {
  return conjugate_on.load(std::memory_order_relaxed);
}

namespace {

using shape_lanes::Lane;
using Mode = SweepConjugate::Mode;

using Values = SweepConjugate::LanePoint;

/// The points each group holds.
template <class Group>
constexpr std::size_t points_per_group = std::tuple_size_v<decltype(Group::p)>;

/// The step of every lane of groups [first, last), their points' values from `before` and
/// `direction` on, in order.
template <Mode M, class Group>
[[gnu::always_inline]] inline void step_lanes(Group* first, Group* last, Values* before,
                                              Values* direction, double beta) {
  const Lane b = Lane{} + beta;
  for (Group* g = first; g != last; ++g) {
    for (auto& point : g->p) {
      SweepConjugate::step<M>(point.ln, before->ln, direction->ln, b);
      SweepConjugate::step<M>(point.lt, before->lt, direction->lt, b);
      ++before, ++direction;
    }
  }
}

template <Mode M, class Group>
[[gnu::noinline]] void lanes_baseline(Group* first, Group* last, Values* before, Values* direction,
                                      double beta) {
  step_lanes<M>(first, last, before, direction, beta);
}
#if FIXSTEP_HAS_SIMD_CLONES
template <Mode M, class Group>
FIXSTEP_TARGET_AVX2 void lanes_avx2(Group* first, Group* last, Values* before, Values* direction,
                                    double beta) {
  step_lanes<M>(first, last, before, direction, beta);
}
template <Mode M, class Group>
FIXSTEP_TARGET_AVX512VL void lanes_avx512(Group* first, Group* last, Values* before,
                                          Values* direction, double beta) {
  step_lanes<M>(first, last, before, direction, beta);
}
#endif

template <Mode M, class Group>
void lanes(SimdLevel level, Group* first, Group* last, Values* before, Values* direction,
           double beta) {
  if (first == last) return;
#if FIXSTEP_HAS_SIMD_CLONES
  if (level == SimdLevel::avx512 && simd_avx512vl()) {
    return lanes_avx512<M>(first, last, before, direction, beta);
  }
  if (level != SimdLevel::baseline) return lanes_avx2<M>(first, last, before, direction, beta);
#endif
  (void)level;
  lanes_baseline<M>(first, last, before, direction, beta);
}

}  // namespace

void ShapeWorld::start_conjugate(SecondThread* thread) {
  SweepConjugate& c = conjugate_;
  c.before.resize(points_per_group<shape_lanes::BlockLanes> * block_lanes_.size() +
                  points_per_group<shape_lanes::PointLanes> * point_lanes_.size());
  c.direction.resize(c.before.size());
  std::size_t rows = 0;
  for (const Unit u : units_) rows += u.rows;
  c.unit_before.resize(3 * rows), c.unit_direction.resize(3 * rows);
  c.v_before.resize(velocity_.size()), c.v_direction.resize(velocity_.size());
  c.last = 0.0;
  // A restart's pass keeps every value as the sweep's start (the tick's first step, Mode::first,
  // sets every direction).
  step_conjugate_as<Mode::restart>(0.0, thread);
}

template <SweepConjugate::Mode M>
void ShapeWorld::step_conjugate_as(double beta, SecondThread* thread) {
  SweepConjugate& c = conjugate_;
  const SimdLevel level = simd_level();
  constexpr std::size_t per_block = points_per_group<shape_lanes::BlockLanes>;
  constexpr std::size_t per_point = points_per_group<shape_lanes::PointLanes>;
  Values* const points = c.before.data() + per_block * block_lanes_.size();
  Values* const point_directions = c.direction.data() + per_block * block_lanes_.size();
  run_halves(thread, block_lanes_.size(), [&](std::size_t begin, std::size_t end, int) {
    lanes<M>(level, block_lanes_.data() + begin, block_lanes_.data() + end,
             c.before.data() + per_block * begin, c.direction.data() + per_block * begin, beta);
  });
  run_halves(thread, point_lanes_.size(), [&](std::size_t begin, std::size_t end, int) {
    lanes<M>(level, point_lanes_.data() + begin, point_lanes_.data() + end,
             points + per_point * begin, point_directions + per_point * begin, beta);
  });
  double* before = c.unit_before.data();
  double* p = c.unit_direction.data();
  for (const Unit u : units_) {
    for (std::size_t i = u.start; i < u.start + u.rows; ++i, before += 3, p += 3) {
      SweepConjugate::step<M>(solve_[i].ln, before[0], p[0], beta);
      SweepConjugate::step<M>(solve_[i].lt, before[1], p[1], beta);
      SweepConjugate::step<M>(rows_[i].lr, before[2], p[2], beta);
    }
  }
  if (rest_.live.size() == state_.size()) {  // every body live, in order: the velocities flat
    static_assert(sizeof(ShapeMotion) == 3 * sizeof(double));
    double* const v = &velocity_.data()->vx;
    double* const was = &c.v_before.data()->vx;
    double* const d = &c.v_direction.data()->vx;
    run_halves(thread, 3 * state_.size(), [&](std::size_t begin, std::size_t end, int) {
      for (std::size_t i = begin; i < end; ++i) SweepConjugate::step<M>(v[i], was[i], d[i], beta);
    });
    return;
  }
  each_live(thread, [&](std::uint32_t b) {
    ShapeMotion &v = velocity_[b], &was = c.v_before[b], &d = c.v_direction[b];
    SweepConjugate::step<M>(v.vx, was.vx, d.vx, beta);
    SweepConjugate::step<M>(v.vy, was.vy, d.vy, beta);
    SweepConjugate::step<M>(v.w, was.w, d.w, beta);
  });
}

void ShapeWorld::step_conjugate(double change, bool first, SecondThread* thread) {
  const double last = conjugate_.last;
  conjugate_.last = change;
  if (first) return step_conjugate_as<Mode::first>(0.0, thread);
  // β ≤ 1 exactly when the change did not grow; it is formed only then, from a last change
  // above 0 (no division by 0, no overflow), and only where it is a normal number. A change
  // that grew, or a NaN, restarts.
  const double ratio = last > 0.0 && change <= last ? change / last : 0.0;
  if (ratio >= 1e-100) return step_conjugate_as<Mode::move>(ratio * ratio, thread);
  step_conjugate_as<Mode::restart>(0.0, thread);
}

}  // namespace fixstep::detail
