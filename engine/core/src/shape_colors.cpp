// Shape contacts, part 3a: the velocity sweeps' colours (shape_sweep.cpp sweeps them). The
// manifolds are coloured greedily in row order, so that no two manifolds of a colour move one
// body; each colour's two-point blocks and one-point manifolds are then packed four at a time
// into the lanes of shape_lanes.hpp, the rest kept as units, and after the sweeps the lanes'
// impulses go back to the rows. Colouring also counts each colour's blocks, points and units,
// which places every colour's groups before any is packed: a large world packs its colours
// by halves on the second thread, each half writing its own colours' groups where one thread
// would have put them.
#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <span>
#include <vector>

#include "shape_lanes.hpp"
#include "shape_world.hpp"

namespace fixstep::detail {

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

using shape_lanes::LaneBodies;

/// Where a manifold goes in its colour: a block's lane, a one-point manifold's lane, or
/// units_ (a redundant point, rolling resistance, the overflow colour, the lanes off).
enum ColorKind : std::uint8_t { block_kind, point_kind, unit_kind };

ColorKind kind_of(const ShapeSolveRow& h, std::uint32_t rows, int color, bool lanes) {
  const bool block = h.flags & ShapeSolveRow::block_first;
  const bool plain = !(h.flags & (ShapeSolveRow::rolls | ShapeSolveRow::redundant));
  if (!lanes || color == overflow || !plain || !(block || rows == 1)) return unit_kind;
  return block ? block_kind : point_kind;
}

/// A group with every lane empty: masses 0, reading the zero slot, writing nothing.
template <class Group>
void clear_group(Group& g, std::uint32_t zero) {
  g = Group{};
  g.read_a.fill(zero), g.read_b.fill(zero);
  g.write_a.fill(shape_lanes::no_write), g.write_b.fill(shape_lanes::no_write);
  g.row.fill(~std::uint32_t{0});
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

constexpr std::uint32_t groups_of(std::uint32_t lanes) {
  return (lanes + shape_lanes::width - 1) / shape_lanes::width;
}

}  // namespace

// Greedy, in row order: each manifold takes a colour none of its moving bodies has taken.
void ShapeWorld::color_manifolds() {
  const std::size_t n = solve_.size();
  for (const std::uint32_t k : rest_.live) body_colors_[k] = 0;  // a resting body takes none
  colored_.clear();
  color_kinds_.assign(color_count + 1, {});
  const bool lanes = shape_lanes::lanes_enabled();
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
    const ColorKind kind = kind_of(h, rows, c, lanes);
    ++color_kinds_[static_cast<std::size_t>(c)][kind];
    colored_.push_back(
        {{static_cast<std::uint32_t>(i), rows}, static_cast<std::uint32_t>(c), kind});
    ++count[c + 1];
    i += rows;
  }
  for (std::size_t c = 1; c < count.size(); ++c) count[c] += count[c - 1];
  by_color_.resize(colored_.size());
  for (std::uint32_t u = 0; u < colored_.size(); ++u) by_color_[count[colored_[u].color]++] = u;
}

// Each colour's place: its groups and units after the colours before it. A colour's lone block
// or one-point manifold is solved alone, after its units: a group of one lane would cost four
// (few manifolds a colour: a car's wheels, a body on a plane).
void ShapeWorld::place_colors() {
  color_places_.clear(), color_runs_.clear();
  ColorRun end;
  std::uint32_t first = 0;
  for (std::size_t c = 0; c < color_kinds_.size(); ++c) {
    const auto& k = color_kinds_[c];
    const std::uint32_t manifolds = k[block_kind] + k[point_kind] + k[unit_kind];
    if (manifolds == 0) continue;
    const ColorPlace place{first,        first + manifolds,  end,
                           k[unit_kind], k[block_kind] == 1, k[point_kind] == 1};
    const ColorRun from = end;
    end.blocks_end += place.lone_block ? 0 : groups_of(k[block_kind]);
    end.points_end += place.lone_point ? 0 : groups_of(k[point_kind]);
    end.units_end += k[unit_kind] + (place.lone_block ? 1 : 0) + (place.lone_point ? 1 : 0);
    const std::uint32_t lanes =
        shape_lanes::width * (end.blocks_end - from.blocks_end + end.points_end - from.points_end);
    end.splits = c != overflow && lanes + end.units_end - from.units_end >= min_split_manifolds;
    color_places_.push_back(place);
    color_runs_.push_back(end);
    first += manifolds;
  }
}

// Each colour's two-point blocks and one-point manifolds (without rolling resistance) into
// groups of four, the last group of a colour padded with empty lanes; the rest into units_.
void ShapeWorld::pack_color(std::size_t k, std::uint32_t zero) {
  const ColorPlace& place = color_places_[k];
  std::array<std::uint32_t, 3> next{};  // the colour's blocks, points and units so far
  const std::uint32_t lone_at = place.start.units_end + place.units;  // after its units
  for (std::uint32_t j = place.first; j < place.end; ++j) {
    const ColoredUnit& cu = colored_[by_color_[j]];
    const Unit u = cu.unit;
    const ShapeSolveRow& h = solve_[u.start];
    if (cu.kind == unit_kind) {
      units_[place.start.units_end + next[unit_kind]++] = u;
    } else if (cu.kind == block_kind && place.lone_block) {
      units_[lone_at] = u;
    } else if (cu.kind == point_kind && place.lone_point) {
      units_[lone_at + (place.lone_block ? 1 : 0)] = u;
    } else if (cu.kind == block_kind) {
      const std::uint32_t at = next[block_kind]++;
      const auto lane = static_cast<int>(at % shape_lanes::width);
      shape_lanes::BlockLanes& g = block_lanes_[place.start.blocks_end + at / shape_lanes::width];
      if (lane == 0) clear_group(g, zero);
      fill_bodies(g, lane, h, u.start, zero);
      g.k12[lane] = h.k12, g.m11[lane] = h.block_mass[0];
      g.m12[lane] = h.block_mass[1], g.m22[lane] = h.block_mass[2];
      fill_point(g.p[0], lane, h), fill_point(g.p[1], lane, solve_[u.start + 1]);
    } else {
      const std::uint32_t at = next[point_kind]++;
      const auto lane = static_cast<int>(at % shape_lanes::width);
      shape_lanes::PointLanes& g = point_lanes_[place.start.points_end + at / shape_lanes::width];
      if (lane == 0) clear_group(g, zero);
      fill_bodies(g, lane, h, u.start, zero);
      fill_point(g.p[0], lane, h);
    }
  }
}

void ShapeWorld::pack_lanes(SecondThread* thread) {
  place_colors();
  const ColorRun end = color_runs_.empty() ? ColorRun{} : color_runs_.back();
  block_lanes_.resize(end.blocks_end), point_lanes_.resize(end.points_end);
  units_.resize(end.units_end);
  const std::uint32_t zero = zero_slot();
  // By halves of the colours: the first half's colours up to half the manifolds.
  std::size_t cut = 0;
  while (cut < color_places_.size() &&
         2 * std::size_t{color_places_[cut].end} <= by_color_.size()) {
    ++cut;
  }
  auto part = [&](int h) {
    const std::size_t from = h == 0 ? 0 : cut, to = h == 0 ? cut : color_places_.size();
    for (std::size_t k = from; k < to; ++k) pack_color(k, zero);
  };
  if (thread != nullptr) {
    thread->both(part);
  } else {
    part(0), part(1);
  }
}

void ShapeWorld::unpack_lanes(SecondThread* thread) {
  const int parts = thread != nullptr ? 2 : 1;
  auto lanes = [&](int part) {
    unpack(block_lanes_, solve_, part, parts);
    unpack(point_lanes_, solve_, part, parts);
  };
  if (thread != nullptr) {
    thread->both(lanes);
  } else {
    lanes(0);
  }
  // Then each row's impulses back into rows_ (once every lane's are in solve_).
  run_halves(thread, solve_.size(), [&](std::size_t begin, std::size_t end, int /*half*/) {
    for (std::size_t i = begin; i < end; ++i)
      rows_[i].ln = solve_[i].ln, rows_[i].lt = solve_[i].lt;
  });
}

}  // namespace fixstep::detail
