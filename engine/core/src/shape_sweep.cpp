// Shape contacts, part 3: the velocity sweeps (shape_world.hpp has the whole tick; the colours
// and lanes are made in shape_colors.cpp). Each sweep solves the joints' rows, then the
// manifolds colour by colour: a colour is a set of manifolds
// of which no two move the same body (greedy graph colouring, as Box2D v3's constraint graph
// does; the method of "High-Performance Physical Simulations on Next-Generation Architecture
// with Many Cores", Intel Technology Journal 11(4), 2007), so the manifolds of a colour may be
// solved in any order, or side by side, with the same result. A colour's two-point blocks and
// its one-point manifolds go four at a time through the lanes of a vector (shape_lanes.hpp),
// two such groups at once (their steps interleaved, so that the processor overlaps the two
// chains of dependent arithmetic); the rest (a redundant point, rolling resistance, the overflow
// colour) one at a time. Either way each manifold's arithmetic is that of shape_rows.hpp, so the
// bits do not depend on the vector width the CPU offers.
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>

#include "fixstep/core/simd.hpp"
#include "shape_lane_rows.hpp"
#include "shape_rows.hpp"
#include "shape_world.hpp"
#include "simd_targets.hpp"

namespace fixstep::detail {

namespace shape_lanes {
namespace {
std::atomic<bool> enabled{true};
}  // namespace
void set_lanes_enabled(bool on) {
  enabled.store(on, std::memory_order_relaxed);
}
bool lanes_enabled() {
  return enabled.load(std::memory_order_relaxed);
}
}  // namespace shape_lanes

using namespace shape_rows;

namespace {

using shape_lanes::BlockLanes;
using shape_lanes::PointLanes;

// The groups of one colour, compiled for each SimdLevel (fixstep/core/simd.hpp; internal
// linkage and everything inlined, as world_step.cpp's sweeps); at the AVX-512 level with
// AVX-512VL, whose 32 vector registers hold the two groups solve_two interleaves. Each returns
// the largest change of a row's own velocity (shape_lanes::note_change).
template <class Group>
[[gnu::noinline]] double groups_baseline(Group* first, Group* last, ShapeMotion* v) {
  return shape_lanes::solve_groups(first, last, v);
}
#if FIXSTEP_HAS_SIMD_CLONES
template <class Group>
FIXSTEP_TARGET_AVX2 double groups_avx2(Group* first, Group* last, ShapeMotion* v) {
  return shape_lanes::solve_groups(first, last, v);
}
template <class Group>
FIXSTEP_TARGET_AVX512VL double groups_avx512(Group* first, Group* last, ShapeMotion* v) {
  return shape_lanes::solve_groups(first, last, v);
}
#endif

template <class Group>
double solve_groups(SimdLevel level, Group* first, Group* last, ShapeMotion* v) {
  if (first == last) return 0.0;
#if FIXSTEP_HAS_SIMD_CLONES
  if (level == SimdLevel::avx512 && simd_avx512vl()) return groups_avx512(first, last, v);
  if (level != SimdLevel::baseline) return groups_avx2(first, last, v);
#endif
  (void)level;
  return groups_baseline(first, last, v);
}

/// The change of a row's own normal and tangent velocity its impulses' change since ln, lt
/// made (|Δλ| K, m/s): shape_lanes::note_change for one row.
double row_change(const ShapeSolveRow& h, double ln, double lt) {
  return std::max(std::abs(h.ln - ln) * h.kn, std::abs(h.lt - lt) * h.kt);
}

}  // namespace

// One manifold: a block's friction and normal rows, or each row's.
double ShapeWorld::solve_unit(Unit u) {
  ShapeSolveRow* const rows = solve_.data();
  double change = 0.0;
  for (std::size_t i = u.start, end = u.start + u.rows; i < end; ++i) {
    ShapeSolveRow& h = rows[i];
    const double ln = h.ln, lt = h.lt;
    Motion2 m = load(h);  // the two bodies' velocities, carried through the manifold's rows
    if (h.flags & ShapeSolveRow::block_first) {  // friction first, bounded by this
      ShapeSolveRow& h2 = rows[i + 1];           // iteration's normal impulse
      const double ln2 = h2.ln, lt2 = h2.lt;
      solve_friction(h, m.a, m.b);
      solve_friction(h2, m.a, m.b);
      solve_block(h, h2, m.a, m.b);
      store(h, m);
      change = std::max({change, row_change(h, ln, lt), row_change(h2, ln2, lt2)});
      if (h.flags & ShapeSolveRow::rolls) {
        change = std::max(change, solve_rolling(rows_[i], h.ln + h2.ln));
      }
      ++i;
    } else {
      if (!(h.flags & ShapeSolveRow::redundant)) {
        solve_friction(h, m.a, m.b), solve_normal(h, m.a, m.b);
        store(h, m);
        change = std::max(change, row_change(h, ln, lt));
      }
      if (h.flags & ShapeSolveRow::rolls) {  // a manifold's first row, maybe redundant:
        const bool pair = h.flags & ShapeSolveRow::rolls_pair;  // both its rows'
        change = std::max(change, solve_rolling(rows_[i], h.ln + (pair ? rows[i + 1].ln : 0.0)));
      }
    }
  }
  return change;
}

double ShapeWorld::sweep_color(const ColorRun& from, const ColorRun& run, SimdLevel level,
                               SecondThread* thread) {
  ShapeMotion* const v = velocity_.data();
  std::array<double, 2> change{};  // each half's
  auto part = [&](int half, int halves) {
    auto cut = [&](std::uint32_t begin, std::uint32_t end, int k) {
      return begin + static_cast<std::uint32_t>((std::uint64_t{end - begin} * k) / halves);
    };
    const std::uint32_t b0 = cut(from.blocks_end, run.blocks_end, half);
    const std::uint32_t b1 = cut(from.blocks_end, run.blocks_end, half + 1);
    const std::uint32_t p0 = cut(from.points_end, run.points_end, half);
    const std::uint32_t p1 = cut(from.points_end, run.points_end, half + 1);
    double most = solve_groups(level, block_lanes_.data() + b0, block_lanes_.data() + b1, v);
    most =
        std::max(most, solve_groups(level, point_lanes_.data() + p0, point_lanes_.data() + p1, v));
    const std::uint32_t u1 = cut(from.units_end, run.units_end, half + 1);
    for (std::uint32_t u = cut(from.units_end, run.units_end, half); u < u1; ++u) {
      most = std::max(most, solve_unit(units_[u]));
    }
    change[half] = most;
  };
  if (thread == nullptr || !run.splits) {
    part(0, 1);
    return change[0];
  }
  auto job = [&](int half) { part(half, 2); };
  thread->both(job);
  ++split_colors_;
  return std::max(change[0], change[1]);
}

int ShapeWorld::solve_velocities(const ShapeTick& tick, SecondThread* second) {
  color_manifolds();
  // (By halves where the shape phase's run holds the second thread.)
  pack_lanes(halved_ ? second : nullptr);
  const SimdLevel level = simd_level();
  split_colors_ = 0;
  // Two threads only where some colour is worth splitting; the run keeps the worker spinning
  // between the colours (nothing if the discs' run holds it open already).
  const bool splits = std::any_of(color_runs_.begin(), color_runs_.end(),
                                  [](const ColorRun& run) { return run.splits; });
  SecondThread* const thread = splits ? second : nullptr;
  const SecondThreadRun team(thread);
  const bool rows = !rest_.live_joints.empty() || !color_runs_.empty();
  // Accelerated (sweep_conjugate.hpp) where the contacts' rows are the only ones (no live
  // joint): a step after every sweep but the last, so that the normal impulses the tick keeps
  // are a sweep's (>= 0; a friction impulse was bounded by the normal one before that sweep's,
  // as in every sweep). With 2 sweeps the one step would only set the direction: none.
  const bool conjugate =
      sweeps_conjugate() && rest_.live_joints.empty() && tick.velocity_iterations > 2;
  if (conjugate && !color_runs_.empty()) start_conjugate(thread);
  int sweeps = 0;
  while (rows && sweeps < tick.velocity_iterations) {
    ++sweeps;
    poll_stop();
    const bool moved = !rest_.live_joints.empty() && solve_joint_velocities();
    if (!moved && color_runs_.empty()) break;
    ColorRun from;
    double change = 0.0;
    for (const ColorRun& run : color_runs_) {
      change = std::max(change, sweep_color(from, run, level, thread));
      from = run;
    }
    if (!moved && change <= velocity_sweep_tolerance) break;  // converged
    if (conjugate && sweeps < tick.velocity_iterations) step_conjugate(change, sweeps == 1, thread);
  }
  // (By halves where the shape phase's run holds the second thread.)
  unpack_lanes(halved_ ? second : nullptr);
  return sweeps;
}

}  // namespace fixstep::detail
