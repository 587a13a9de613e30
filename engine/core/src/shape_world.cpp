// Shape contacts, part 1: the manifolds of a tick and the tick in order (shape_world.hpp has
// the whole tick; the broadphase is shape_broadphase.cpp, continuous collision
// shape_continuous.cpp, the solver shape_solver.cpp).
#include "shape_world.hpp"

#include <algorithm>
#include <cmath>

#include "fixstep/core/det_math.hpp"
#include "fixstep/core/limits.hpp"
#include "fixstep/core/stop_request.hpp"
#include "segment_set.hpp"

namespace fixstep::detail {

namespace {

// Whether a shape's box (its vertices grown by its radius and speculative margin, as
// convex_aabb makes it) lies wholly beyond the plane's surface: then no vertex is within the
// margin of it and collide_plane would find no point. The box's corner nearest the plane is
// at least radius + margin nearer than any vertex (the ball of that radius about a vertex is
// in the box); the guard, a millionth of a millimetre per metre of the numbers, keeps rounding
// from ever skipping a point collide_plane would find.
bool clear_of(const Aabb& box, const ShapeWorld::UnitPlane& u) {
  const Vec2 nearest{u.n.x >= 0.0 ? box.lower.x : box.upper.x,
                     u.n.y >= 0.0 ? box.lower.y : box.upper.y};
  const double gap = dot(u.n, nearest) - u.offset;
  const double guard =
      1e-9 * (1.0 + std::abs(u.offset) + std::abs(nearest.x) + std::abs(nearest.y));
  return gap > guard;
}

/// A shape's box as the broadphase keeps it (ShapeWorld::boxes_), as an Aabb.
Aabb aabb_of(const SweptBox& b) {
  return {{b.min_x, b.min_y}, {b.max_x, b.max_y}};
}

}  // namespace

Pose ShapeWorld::pose(std::uint32_t body) const {
  const ShapeState& s = state_[body];
  return {{s.x, s.y}, s.q};
}

Pose ShapeWorld::start_pose(std::uint32_t body) const {
  const ShapeState& s = state_[body];
  return {{s.x0, s.y0}, s.q0};
}

// How far a body's surface may move in the tick on its free motion, plus 4 slops (Box2D v3's
// speculative distance): its start-of-tick boxes grow by this, and a pair's manifold keeps the
// points closer than the sum of its bodies' margins.
double ShapeWorld::margin(std::uint32_t body, double dt) const {
  const ShapedBody& b = bodies_[body];
  const ShapeState& s = state_[body];
  if (b.type == BodyType::static_body) return 0.0;
  return 2.0 * slop + dt * (det::hypot(s.vx, s.vy) + std::abs(s.w) * b.extent);
}

// --- broadphase and manifolds --------------------------------------------------------------

void ShapeWorld::add_manifold(std::vector<ShapeRow>& rows, const Manifold& m, std::uint32_t a,
                              std::uint32_t b, double friction, double restitution, double rolling,
                              std::uint64_t pair) {
  for (int p = 0; p < m.count; ++p) {
    const ManifoldPoint& mp = m.points[p];
    const double roll = p == 0 ? rolling : 0.0;
#if defined(__cpp_aggregate_paren_init)
    // Made in place, every field given in ShapeRow's order (a row is 3 cache lines, and one
    // made by emplace_back() and then assigned was first cleared whole with a string
    // instruction).
    rows.emplace_back(a, b, m.normal, mp.anchor_a, mp.anchor_b, mp.separation, friction,
                      restitution, /*approach*/ 0.0, /*ln*/ 0.0, /*lt*/ 0.0, roll,
                      /*rolling_mass*/ 0.0, /*lr*/ 0.0, /*bn*/ 0.0, /*bt*/ 0.0, pair, mp.id);
#else  // a compiler without parenthesized aggregate initialization (Clang before 16)
    ShapeRow& r = rows.emplace_back();
    r.a = a, r.b = b, r.n = m.normal, r.ra = mp.anchor_a, r.rb = mp.anchor_b;
    r.separation = mp.separation, r.friction = friction, r.restitution = restitution;
    r.rolling = roll, r.pair = pair, r.id = mp.id;
#endif
  }
}

namespace {

double mix_friction(double a, double b) {
  return std::sqrt(a * b);
}

}  // namespace

// The manifolds of candidates_ from `begin` to `end` into `rows`, those a one-way rule or the
// pre-solve hook disables into `disabled`; each sharp pair's manifold, kept from an earlier
// tick while it holds (contact recycling, kept_manifold.hpp) or as made now, into `kept`.
void ShapeWorld::collect_pairs(const ShapeTick& tick, std::size_t begin, std::size_t end,
                               std::vector<ShapeRow>& rows, std::vector<std::uint64_t>& disabled,
                               std::vector<KeptManifold>& kept) {
  auto cursor = kept_.cbegin();
  if (begin < end) {
    const std::uint64_t first = index_pair(candidates_[begin]);
    cursor = std::lower_bound(kept_.cbegin(), kept_.cend(), first,
                              [](const KeptManifold& k, std::uint64_t p) { return k.pair < p; });
  }
  for (std::size_t k = begin; k < end; ++k) {
    const Candidate& c = candidates_[k];
    const ShapeEntry& sa = shapes_[c.a];
    const ShapeEntry& sb = shapes_[c.b];
    const double margin = margin_[sa.owner] + margin_[sb.owner];
    const Pose ta = start_pose(sa.owner), tb = start_pose(sb.owner);
    const double angle_a = state_[sa.owner].a0, angle_b = state_[sb.owner].a0;
    const std::uint64_t index = index_pair(c);
    while (cursor != kept_.cend() && cursor->pair < index) ++cursor;
    const bool recycles = sharp(sa) && sharp(sb);
    const bool held = recycles && cursor != kept_.cend() && cursor->pair == index &&
                      kept_holds(*cursor, ta, angle_a, tb, angle_b, bodies_[sb.owner].extent,
                                 margin, recycle_distance);
    // Made where it lives (a manifold declared first was cleared whole, then assigned).
    const Manifold m =
        held ? recycle(*cursor, ta, tb) : collide(sa.convex, ta, sb.convex, tb, margin);
    if (held) {
      kept.push_back(*cursor);  // measured from where it was made, not from this tick
    } else {
      if (m.count == 0) continue;
      if (recycles) kept.push_back(keep_manifold(index, m, ta, angle_a, tb, angle_b, margin));
    }
    const std::uint64_t pair = std::uint64_t{sa.key} << 32 | sb.key;
    if ((sa.one_way || sb.one_way || tick.pre_solve) &&
        !contact_acts(tick, m, c.a, c.b, -1, -1, nullptr)) {
      disabled.push_back(pair);
      continue;
    }
    const double rolling =
        sa.rolling > 0.0 || sb.rolling > 0.0
            ? std::max(sa.rolling, sb.rolling) * std::max(sa.convex.radius, sb.convex.radius)
            : 0.0;
    add_manifold(rows, m, sa.owner, sb.owner, mix_friction(sa.friction, sb.friction),
                 std::max(sa.restitution, sb.restitution), rolling, pair);
  }
}

void ShapeWorld::collect(const ShapeTick& tick, SecondThread* thread) {
  rows_.clear(), disabled_.clear();
  unit_planes_.clear();
  for (const PlaneDef& pl : tick.planes) {
    const double len = det::hypot(pl.normal.x, pl.normal.y);
    unit_planes_.push_back({pl.normal / len, pl.offset / len});
  }
  // By halves on two threads, the second's rows then put after the first's (the same rows in
  // the same order), unless a pre-solve hook is set: the game's code runs on the caller's
  // thread, in order.
  const std::size_t n = candidates_.size();
  next_kept_.clear();
  if (thread != nullptr && !tick.pre_solve) {
    half_rows_.clear(), half_disabled_.clear(), half_kept_.clear();
    auto job = [&](int h) {
      if (h == 0) collect_pairs(tick, 0, n / 2, rows_, disabled_, next_kept_);
      if (h == 1) collect_pairs(tick, n / 2, n, half_rows_, half_disabled_, half_kept_);
    };
    thread->both(job);
    rows_.insert(rows_.end(), half_rows_.begin(), half_rows_.end());
    disabled_.insert(disabled_.end(), half_disabled_.begin(), half_disabled_.end());
    next_kept_.insert(next_kept_.end(), half_kept_.begin(), half_kept_.end());
  } else {
    collect_pairs(tick, 0, n, rows_, disabled_, next_kept_);
  }
  kept_.swap(next_kept_);
  for (const std::uint32_t i : rest_.live) {  // the awake bodies' shapes, in shape order
    const ShapedBody& b = bodies_[i];
    if (!awake(b) || b.disc) continue;
    for (std::uint32_t k = b.first; k < b.first + b.count; ++k) collect_surfaces(tick, k);
  }
  std::sort(disabled_.begin(), disabled_.end());
}

std::span<const std::uint32_t> ShapeWorld::near_segments(const ShapeTick& tick, const Aabb& box) {
  near_segments_.clear();
  if (tick.segments.empty()) return {};
  tick.segment_grid->query(box.lower.x, box.lower.y, box.upper.x, box.upper.y, near_segments_);
  return near_segments_;
}

// The manifolds of an awake body's shape k with the planes and segments.
void ShapeWorld::collect_surfaces(const ShapeTick& tick, std::uint32_t k) {
  const ShapeEntry& e = shapes_[k];
  if (e.sensor) return;
  const Pose at = start_pose(e.owner);
  const double margin = margin_[e.owner];
  for (std::uint32_t p = 0; p < tick.planes.size(); ++p) {
    const PlaneDef& pl = tick.planes[p];
    const UnitPlane& u = unit_planes_[p];
    if (clear_of(aabb_of(boxes_[k]), u)) continue;
    const Manifold m = collide_plane(u.n, u.offset, e.convex, at, margin);
    if (m.count == 0) continue;
    const std::uint64_t pair = std::uint64_t{0xF0000000u | p} << 32 | e.key;
    if ((e.one_way || tick.pre_solve) &&
        !contact_acts(tick, m, none, k, static_cast<int>(p), -1, nullptr)) {
      disabled_.push_back(pair);
      continue;
    }
    add_manifold(rows_, m, none, e.owner, mix_friction(pl.friction, e.friction),
                 std::max(pl.restitution, e.restitution), e.rolling * e.convex.radius, pair);
  }
  const Aabb box = aabb_of(boxes_[k]);
  for (const std::uint32_t s : near_segments(tick, box)) {
    const SegmentDef& seg = tick.segments[s];
    if (!boxes_overlap(box, segment_bounds(seg))) continue;
    const Manifold m = collide_segment(seg, e.convex, at, margin);
    if (m.count == 0) continue;
    const std::uint64_t pair = std::uint64_t{0xE0000000u | s} << 32 | e.key;
    if (e.one_way || seg.one_way || tick.pre_solve) {
      const Vec2 up = seg.one_way ? one_way_up_of(seg) : Vec2{};
      if (!contact_acts(tick, m, none, k, -1, static_cast<int>(s), seg.one_way ? &up : nullptr)) {
        disabled_.push_back(pair);
        continue;
      }
    }
    add_manifold(rows_, m, none, e.owner, mix_friction(seg.friction, e.friction),
                 std::max(seg.restitution, e.restitution), e.rolling * e.convex.radius, pair);
  }
}

void ShapeWorld::detect_sensors() {
  sensed_.clear();
  std::sort(
      sensor_candidates_.begin(), sensor_candidates_.end(),
      [](const Candidate& l, const Candidate& r) { return l.a != r.a ? l.a < r.a : l.b < r.b; });
  for (const Candidate& c : sensor_candidates_) {
    const ShapeEntry& s = shapes_[c.a];
    const ShapeEntry& v = shapes_[c.b];
    const Distance d = distance(s.convex, pose(s.owner), v.convex, pose(v.owner));
    if (!(d.overlap || d.distance < 0.0)) continue;
    const Sensed e{s.owner, v.owner};
    if (std::find(sensed_.begin(), sensed_.end(), e) == sensed_.end()) sensed_.push_back(e);
  }
}

// The few pairs whose lower end is the lower body (a body's joints), searched in turn.
bool ShapeWorld::unpaired(std::uint32_t a, std::uint32_t b) const {
  const std::uint32_t low = std::min(a, b);
  if (std::size_t{low} + 1 >= unpaired_start_.size()) return false;
  const std::uint64_t key = std::uint64_t{low} << 32 | std::max(a, b);
  for (std::uint32_t k = unpaired_start_[low], end = unpaired_start_[low + 1]; k < end; ++k) {
    if (unpaired_[k] == key) return true;
  }
  return false;
}

bool ShapeWorld::moving(std::uint32_t body) const {
  const ShapedBody& b = bodies_[body];
  if (b.type != BodyType::kinematic) return awake(b);
  const ShapeState& s = state_[body];
  return s.vx != 0.0 || s.vy != 0.0 || s.w != 0.0;
}

ShapeTally ShapeWorld::solve(const ShapeTick& tick) {
  ShapeTally tally;
  joints_ = tick.joints, unpaired_ = tick.unpaired, unpaired_start_ = tick.unpaired_start;
  visited_ = !rest_.stale ? rest_.live.size() : rest_.whole ? bodies_.size() : visit_few().size();
  joints_visited_ = 0;
  // The second thread, with two: the discs' where its run is open, else the shape world's
  // own. A large world makes its rotations, broadphase and manifolds by halves on it (the run
  // keeps the worker spinning through the shape phase); the velocity sweeps split their large
  // colours.
  SecondThread* const second = tick.threads < 2         ? nullptr
                               : tick.thread != nullptr ? tick.thread
                                                        : &second_;
  SecondThread* const thread = shapes_.size() >= min_split_shapes ? second : nullptr;
  const SecondThreadRun team(thread);
  halved_ = thread != nullptr;
  dt_ = tick.dt;  // (the fat boxes reach ahead by it, the solver steps by it)
  if (rest_.stale) {
    rebuild_rest(tick.dt);
  } else {
    rot_each_live(
        thread, [&](std::uint32_t i) { return state_[i].a0; },
        [&](std::uint32_t i, Rot q) { state_[i].q0 = q; });
  }
  bool paired = broadphase(tick.dt, tally, thread);
  if (paired && !wake_.empty() && tick.wake) {  // sleepers woken: paired again as they now are
    tick.wake(tick.wake_context);
    if (rest_.stale) {  // (the wake makes it so)
      if (rest_.whole) visited_ = bodies_.size();
      rebuild_rest(tick.dt);
    }
    paired = broadphase(tick.dt, tally, thread);
  }
  if (!paired) {  // a work limit: the tick's shape contacts unresolved
    rows_.clear(), kept_.clear();
    return tally;
  }
  collect(tick, thread);
  tally.pairs = candidates_.size();
  tally.points = rows_.size();
  prepare_rows(tick, thread);
  joint_thread_ = second;  // the joints' passes by halves where prepare_joints splits them
  prepare_joints();
  const SecondThreadRun joints_team(joints_halved_ ? joint_thread_ : nullptr);
  tally.velocity_sweeps = solve_velocities(tick, second);
  follow_velocities();
  account_joints();
  continuous(tick, tally);
  solve_positions(tick, second, tally);
  keep_impulses();
  if (!sensor_candidates_.empty() || !sensed_.empty()) detect_sensors();
  throw_if_stop_requested();
  return tally;
}

}  // namespace fixstep::detail
