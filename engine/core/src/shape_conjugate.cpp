// The shape contacts' velocity sweeps, accelerated: the conjugate step after each sweep
// (sweep_conjugate.hpp says what it is and why the velocities may follow the impulses body by
// body). Every value's step is element-wise arithmetic, the same for a lane and a scalar, so the
// bits do not depend on the vector width, on whether the manifolds go through the lanes, or on
// how the passes are split between two threads.
#include <atomic>
#include <cstddef>
#include <tuple>
#include <vector>

#include "shape_world.hpp"

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

/// Lanes [begin, end) of the groups' impulses, each group's points' ln and lt in turn, from
/// `first` in `before` and `direction`.
template <class Group, class F>
void each_lane(std::vector<Group>& groups, std::size_t begin, std::size_t end, std::size_t first,
               F&& f) {
  constexpr std::size_t per = 2 * std::tuple_size_v<decltype(Group::p)>;
  for (std::size_t g = begin; g < end; ++g) {
    std::size_t k = first + g * per;
    for (auto& point : groups[g].p) f(point.ln, k), f(point.lt, k + 1), k += 2;
  }
}

}  // namespace

void ShapeWorld::start_conjugate(SecondThread* thread) {
  SweepConjugate& c = conjugate_;
  const std::size_t lanes = 4 * block_lanes_.size() + 2 * point_lanes_.size();
  c.before.resize(lanes), c.direction.resize(lanes);
  std::size_t rows = 0;
  for (const Unit u : units_) rows += u.rows;
  c.unit_before.resize(3 * rows), c.unit_direction.resize(3 * rows);
  c.v_before.resize(velocity_.size()), c.v_direction.resize(velocity_.size());
  c.last = 0.0;
  const std::size_t points = 4 * block_lanes_.size();
  run_halves(thread, block_lanes_.size(), [&](std::size_t begin, std::size_t end, int) {
    each_lane(block_lanes_, begin, end, 0, [&](Lane& x, std::size_t k) { c.before[k] = x; });
  });
  run_halves(thread, point_lanes_.size(), [&](std::size_t begin, std::size_t end, int) {
    each_lane(point_lanes_, begin, end, points, [&](Lane& x, std::size_t k) { c.before[k] = x; });
  });
  std::size_t k = 0;
  for (const Unit u : units_) {
    for (std::size_t i = u.start; i < u.start + u.rows; ++i, k += 3) {
      c.unit_before[k] = solve_[i].ln, c.unit_before[k + 1] = solve_[i].lt;
      c.unit_before[k + 2] = rows_[i].lr;
    }
  }
  each_live(thread, [&](std::uint32_t b) { c.v_before[b] = velocity_[b]; });
}

void ShapeWorld::step_conjugate(double change, bool first, SecondThread* thread) {
  SweepConjugate& c = conjugate_;
  const double ratio = change / c.last;
  const double beta = ratio * ratio;
  // (A NaN, or a last change of 0, restarts as a growing change does.)
  const Mode mode = first ? Mode::first : beta <= 1.0 ? Mode::move : Mode::restart;
  c.last = change;
  const Lane lane_beta = Lane{} + beta;
  auto lane = [&](Lane& x, std::size_t k) {
    SweepConjugate::step(x, c.before[k], c.direction[k], lane_beta, mode);
  };
  const std::size_t points = 4 * block_lanes_.size();
  run_halves(thread, block_lanes_.size(), [&](std::size_t begin, std::size_t end, int) {
    each_lane(block_lanes_, begin, end, 0, lane);
  });
  run_halves(thread, point_lanes_.size(), [&](std::size_t begin, std::size_t end, int) {
    each_lane(point_lanes_, begin, end, points, lane);
  });
  std::size_t k = 0;
  for (const Unit u : units_) {
    for (std::size_t i = u.start; i < u.start + u.rows; ++i, k += 3) {
      ShapeSolveRow& h = solve_[i];
      SweepConjugate::step(h.ln, c.unit_before[k], c.unit_direction[k], beta, mode);
      SweepConjugate::step(h.lt, c.unit_before[k + 1], c.unit_direction[k + 1], beta, mode);
      SweepConjugate::step(rows_[i].lr, c.unit_before[k + 2], c.unit_direction[k + 2], beta, mode);
    }
  }
  each_live(thread, [&](std::uint32_t b) {
    ShapeMotion &v = velocity_[b], &before = c.v_before[b], &p = c.v_direction[b];
    SweepConjugate::step(v.vx, before.vx, p.vx, beta, mode);
    SweepConjugate::step(v.vy, before.vy, p.vy, beta, mode);
    SweepConjugate::step(v.w, before.w, p.w, beta, mode);
  });
}

}  // namespace fixstep::detail
