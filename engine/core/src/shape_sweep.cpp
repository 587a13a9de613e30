// Shape contacts, part 3: the velocity sweeps (shape_world.hpp has the whole tick). Each sweep
// solves the joints' rows, then the manifolds colour by colour: a colour is a set of manifolds
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
#include <bit>
#include <cmath>
#include <span>
#include <utility>

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

/// Colours a manifold may take (a bit each in a body's mask); a manifold that finds none free
/// goes to the overflow colour, solved last and one at a time.
constexpr int color_count = 64;
constexpr int overflow = color_count;
/// The highest colours are kept for manifolds against what does not move, which take the
/// highest colour free: Box2D v3 solves them after those between two moving bodies, so that
/// the supports, solved last in a sweep, hold.
constexpr int dynamic_colors = color_count - 4;

int color_of(std::uint64_t used, bool both_move) {
  if (both_move) {
    const int low = std::countr_zero(~(used | ~((std::uint64_t{1} << dynamic_colors) - 1)));
    return low < dynamic_colors ? low : overflow;
  }
  const std::uint64_t free = ~used & ~std::uint64_t{1};
  return free != 0 ? color_count - 1 - std::countl_zero(free) : overflow;
}

using shape_lanes::BlockLanes;
using shape_lanes::LaneBodies;
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

/// A lane's bodies and shared fields from a manifold's first row `h` (row i of solve_).
void fill_bodies(LaneBodies& g, int lane, const ShapeSolveRow& h, std::uint32_t i,
                 std::uint32_t zero) {
  const bool move_a = h.a != ShapeWorld::none && (h.ma > 0.0 || h.ia > 0.0);
  const bool move_b = h.mb > 0.0 || h.ib > 0.0;
  g.read_a[lane] = h.a != ShapeWorld::none ? h.a : zero, g.read_b[lane] = h.b;
  g.write_a[lane] = move_a ? h.a : shape_lanes::no_write;
  g.write_b[lane] = move_b ? h.b : shape_lanes::no_write;
  g.row[lane] = i;
  g.nx[lane] = h.nx, g.ny[lane] = h.ny, g.ma[lane] = h.ma, g.ia[lane] = h.ia;
  g.mb[lane] = h.mb, g.ib[lane] = h.ib, g.friction[lane] = h.friction;
}

void fill_point(shape_lanes::LanePoint& q, int lane, const ShapeSolveRow& h) {
  q.rna[lane] = h.rna, q.rnb[lane] = h.rnb, q.rta[lane] = h.rta, q.rtb[lane] = h.rtb;
  q.kn[lane] = h.kn, q.kt[lane] = h.kt, q.normal_mass[lane] = h.normal_mass;
  q.tangent_mass[lane] = h.tangent_mass, q.target[lane] = h.target;
  q.ln[lane] = h.ln, q.lt[lane] = h.lt;
}

/// The next free lane of a colour's groups in `groups`, `used` of the last group's lanes taken
/// (a new group, its lanes empty, when it is full; a colour starts with `used` = width).
template <class Group>
std::pair<Group*, int> next_lane(std::vector<Group>& groups, int& used, std::uint32_t zero) {
  if (used == shape_lanes::width) {
    Group& g = groups.emplace_back();
    g.read_a.fill(zero), g.read_b.fill(zero);
    g.write_a.fill(shape_lanes::no_write), g.write_b.fill(shape_lanes::no_write);
    g.row.fill(~std::uint32_t{0});
    used = 0;
  }
  return {&groups.back(), used++};
}

/// Part `part` of `parts` of the groups' impulses back into their rows of solve_.
template <class Group>
void unpack(const std::vector<Group>& groups, std::vector<ShapeSolveRow>& solve, int part,
            int parts) {
  const auto u = static_cast<std::size_t>(part), n = static_cast<std::size_t>(parts);
  const std::span<const Group> mine(groups.data() + groups.size() * u / n,
                                    groups.data() + groups.size() * (u + 1) / n);
  for (const Group& g : mine) {
    for (int l = 0; l < shape_lanes::width && g.row[l] != ~std::uint32_t{0}; ++l) {
      for (std::size_t p = 0; p < g.p.size(); ++p) {
        solve[g.row[l] + p].ln = g.p[p].ln[l], solve[g.row[l] + p].lt = g.p[p].lt[l];
      }
    }
  }
}

}  // namespace

// Greedy, in row order: each manifold takes a colour none of its moving bodies has taken.
void ShapeWorld::color_manifolds() {
  const std::size_t n = solve_.size();
  for (const std::uint32_t k : rest_.live) body_colors_[k] = 0;  // a resting body takes none
  colored_.clear();
  std::array<std::uint32_t, color_count + 2> count{};
  for (std::size_t i = 0; i < n;) {
    const std::uint32_t rows = pairs_next(i) ? 2 : 1;
    const ShapeSolveRow& h = solve_[i];
    const bool move_a = h.a != none && (h.ma > 0.0 || h.ia > 0.0);
    const bool move_b = h.mb > 0.0 || h.ib > 0.0;
    const std::uint64_t used = (move_a ? body_colors_[h.a] : 0) | (move_b ? body_colors_[h.b] : 0);
    const int c = move_a || move_b ? color_of(used, move_a && move_b) : 0;
    if (c != overflow) {
      if (move_a) body_colors_[h.a] |= std::uint64_t{1} << c;
      if (move_b) body_colors_[h.b] |= std::uint64_t{1} << c;
    }
    colored_.push_back({{static_cast<std::uint32_t>(i), rows}, static_cast<std::uint32_t>(c)});
    ++count[c + 1];
    i += rows;
  }
  for (std::size_t c = 1; c < count.size(); ++c) count[c] += count[c - 1];
  by_color_.resize(colored_.size());
  for (std::uint32_t u = 0; u < colored_.size(); ++u) by_color_[count[colored_[u].color]++] = u;
}

// Each colour's two-point blocks and one-point manifolds (without rolling resistance) into
// groups of four, the last group of a colour padded with empty lanes; the rest into units_.
void ShapeWorld::pack_lanes() {
  block_lanes_.clear(), point_lanes_.clear(), units_.clear(), color_runs_.clear();
  const std::uint32_t zero = zero_slot();
  const bool lanes = shape_lanes::lanes_enabled();
  for (std::size_t k = 0; k < by_color_.size();) {  // each colour that has manifolds
    const std::uint32_t c = colored_[by_color_[k]].color;
    int blocks = shape_lanes::width, points = shape_lanes::width;  // a colour's groups its own
    for (; k < by_color_.size() && colored_[by_color_[k]].color == c; ++k) {
      const Unit u = colored_[by_color_[k]].unit;
      const std::uint32_t i = u.start;
      const ShapeSolveRow& h = solve_[i];
      const bool block = h.flags & ShapeSolveRow::block_first;
      const bool plain = !(h.flags & (ShapeSolveRow::rolls | ShapeSolveRow::redundant));
      if (!lanes || c == overflow || !plain || !(block || u.rows == 1)) {
        units_.push_back(u);
      } else if (block) {
        const auto [g, lane] = next_lane(block_lanes_, blocks, zero);
        fill_bodies(*g, lane, h, i, zero);
        g->k12[lane] = h.k12, g->m11[lane] = h.block_mass[0];
        g->m12[lane] = h.block_mass[1], g->m22[lane] = h.block_mass[2];
        fill_point(g->p[0], lane, h), fill_point(g->p[1], lane, solve_[i + 1]);
      } else {
        const auto [g, lane] = next_lane(point_lanes_, points, zero);
        fill_bodies(*g, lane, h, i, zero);
        fill_point(g->p[0], lane, h);
      }
    }
    // A colour's lone block or one-point manifold is solved alone: a group of one lane would
    // cost four (few manifolds a colour: a car's wheels, a body on a plane).
    lone_to_units(block_lanes_, blocks, color_runs_.empty() ? 0 : color_runs_.back().blocks_end);
    lone_to_units(point_lanes_, points, color_runs_.empty() ? 0 : color_runs_.back().points_end);
    const ColorRun from = color_runs_.empty() ? ColorRun{} : color_runs_.back();
    ColorRun run{static_cast<std::uint32_t>(block_lanes_.size()),
                 static_cast<std::uint32_t>(point_lanes_.size()),
                 static_cast<std::uint32_t>(units_.size())};
    const std::uint32_t manifolds =
        shape_lanes::width * (run.blocks_end - from.blocks_end + run.points_end - from.points_end) +
        run.units_end - from.units_end;
    run.splits = c != overflow && manifolds >= min_split_manifolds;
    color_runs_.push_back(run);
  }
}

template <class Group>
void ShapeWorld::lone_to_units(std::vector<Group>& groups, int used, std::uint32_t from) {
  if (groups.size() != from + 1 || used != 1) return;
  units_.push_back({groups.back().row[0], static_cast<std::uint32_t>(groups.back().p.size())});
  groups.pop_back();
}

void ShapeWorld::unpack_lanes(SecondThread* thread) {
  const int parts = thread != nullptr ? 2 : 1;
  auto lanes = [&](int part) {
    unpack(block_lanes_, solve_, part, parts);
    unpack(point_lanes_, solve_, part, parts);
  };
  // Then each row's impulses back into rows_ (once every lane's are in solve_).
  auto rows = [&](int part) {
    const auto u = static_cast<std::size_t>(part), n = static_cast<std::size_t>(parts);
    for (std::size_t i = solve_.size() * u / n; i < solve_.size() * (u + 1) / n; ++i) {
      rows_[i].ln = solve_[i].ln, rows_[i].lt = solve_[i].lt;
    }
  };
  if (thread != nullptr) {
    thread->both(lanes);
    thread->both(rows);
  } else {
    lanes(0);
    rows(0);
  }
}

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
  pack_lanes();
  const SimdLevel level = simd_level();
  split_colors_ = 0;
  // Two threads only where some colour is worth splitting; the run keeps the worker spinning
  // between the colours (nothing if the discs' run holds it open already).
  const bool splits = std::any_of(color_runs_.begin(), color_runs_.end(),
                                  [](const ColorRun& run) { return run.splits; });
  SecondThread* const thread = splits ? second : nullptr;
  const SecondThreadRun team(thread);
  const bool rows = !rest_.live_joints.empty() || !color_runs_.empty();
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
  }
  // (By halves where the shape phase's run holds the second thread.)
  unpack_lanes(halved_ ? second : nullptr);
  return sweeps;
}

}  // namespace fixstep::detail
