// Shape contacts, part 1b: which manifolds act. One-way shapes and segments (one_way.hpp: the
// contact's normal leans up and the other body was not crossing at the tick's start), then
// the game's pre-solve hook (pre_solve.hpp), both at the tick's start poses before any row is
// made.
#include <algorithm>
#include <cmath>

#include "one_way.hpp"
#include "shape_world.hpp"

namespace fixstep::detail {

bool ShapeWorld::contact_acts(const ShapeTick& tick, const Manifold& m, std::uint32_t a,
                              std::uint32_t b, int plane, int segment,
                              const Vec2* segment_up) const {
  double lowest = m.points[0].separation;
  for (int p = 1; p < m.count; ++p) lowest = std::min(lowest, m.points[p].separation);
  const ShapeEntry& sb = shapes_[b];
  // Each one-way shape of the pair by its own up, the normal seen from it.
  if (segment_up && !one_way_blocks(*segment_up, m.normal, lowest, one_way_shape_slop)) {
    return false;
  }
  if (a != none && shapes_[a].one_way) {
    const Vec2 up = rotate(state_[shapes_[a].owner].q0, shapes_[a].up);
    if (!one_way_blocks(up, m.normal, lowest, one_way_shape_slop)) return false;
  }
  if (sb.one_way) {
    const Vec2 up = rotate(state_[sb.owner].q0, sb.up);
    if (!one_way_blocks(up, -m.normal, lowest, one_way_shape_slop)) return false;
  }
  if (!tick.pre_solve) return true;
  PreSolveContact c;
  auto shape_index = [&](std::uint32_t k) {
    return bodies_[shapes_[k].owner].disc ? -1 : static_cast<int>(shapes_[k].key & 63u);
  };
  if (a != none) {
    c.a = tick.entities[bodies_[shapes_[a].owner].body];
    c.shape_a = shape_index(a);
  }
  c.b = tick.entities[bodies_[sb.owner].body];
  c.shape_b = shape_index(b);
  c.plane = plane, c.segment = segment;
  c.normal = m.normal;
  c.point_count = m.count;
  for (int p = 0; p < m.count; ++p) {
    c.points[p] = m.points[p].point, c.separations[p] = m.points[p].separation;
  }
  return tick.pre_solve(c, tick.pre_solve_context);
}

}  // namespace fixstep::detail
