// Shape contacts, part 1: continuous collision against what does not move and the manifolds
// of a tick (shape_world.hpp has the whole tick; the broadphase is shape_broadphase.cpp, the
// solver shape_solver.cpp).
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

Aabb segment_bounds(const SegmentDef& s) {
  return {{std::min(s.a.x, s.b.x), std::min(s.a.y, s.b.y)},
          {std::max(s.a.x, s.b.x), std::max(s.a.y, s.b.y)}};
}

Aabb merge(const Aabb& a, const Aabb& b) {
  return {{std::min(a.lower.x, b.lower.x), std::min(a.lower.y, b.lower.y)},
          {std::max(a.upper.x, b.upper.x), std::max(a.upper.y, b.upper.y)}};
}

/// The lowest value of n·x − offset over `c` at pose `t`, radius taken off: the distance of
/// the shape from the plane (< 0: across it).
double plane_distance(Vec2 n, double offset, const Convex& c, const Pose& t) {
  double lowest = INFINITY;
  for (int i = 0; i < c.count; ++i) lowest = std::min(lowest, dot(n, transform(t, c.vertices[i])));
  return lowest - offset - c.radius;
}

/// First fraction in [0, 1] at which `c` on sweep `s` comes within `target` of the plane, by
/// conservative advancement: the distance falls no faster than |n·Δc| + |Δa| · extent a unit
/// of t. 1 when it does not.
double plane_toi(Vec2 n, double offset, const Convex& c, const Sweep& s, double target) {
  const double bound = std::abs(dot(n, s.c1 - s.c0)) + std::abs(s.a1 - s.a0) * extent(c);
  if (!(bound > 0.0)) return 1.0;
  double t = 0.0;
  for (int i = 0; i < 64; ++i) {
    const double d = plane_distance(n, offset, c, pose_at(s, t));
    if (d <= target + 0.25 * target) return t;
    t += (d - target) / bound;
    if (t >= 1.0) return 1.0;
  }
  return t;
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

// --- continuous collision ----------------------------------------------------------------

void ShapeWorld::continuous(const ShapeTick& tick, ShapeTally& tally) {
  bool ready = false;
  for (const std::uint32_t i : rest_.live) {
    const ShapedBody& b = bodies_[i];
    if (!awake(b) || b.disc) continue;
    ShapeState& s = state_[i];
    const double dx = s.x - s.x0, dy = s.y - s.y0, turned = std::abs(s.a - s.a0) * b.extent;
    // |dx| + |dy| bounds the distance from above: a body that moved less than 0.49 of the
    // thinnest by it is not fast, and the square root is left out (the same decision: the
    // bound and the test below differ by far more than their rounding).
    if (std::abs(dx) + std::abs(dy) + turned <= 0.49 * b.thinnest) continue;
    const double motion = det::hypot(dx, dy) + turned;
    if (!(motion > 0.5 * b.thinnest)) continue;  // Box2D v3's test of a fast body
    if (!ready) {                                // once a tick, and only in a tick with a fast body
      row_keys_.clear();
      for (const ShapeRow& r : rows_) row_keys_.push_back(r.pair);
      std::sort(row_keys_.begin(), row_keys_.end());
      ready = true;
    }
    s.q = rot_of(s.a);
    const double t = first_static_touch(i, tick);
    if (t >= 1.0) continue;
    const Sweep sweep{{s.x0, s.y0}, {s.x, s.y}, s.a0, s.a};
    const Pose at = pose_at(sweep, t);
    s.x = at.p.x, s.y = at.p.y, s.a = s.a0 + t * (s.a - s.a0), s.q = at.q;
    ++tally.ccd_hits;
  }
}

// Whether the tick has a row of this pair of shapes (a key names both, the body's among them).
bool ShapeWorld::has_row(std::uint64_t pair) const {
  return std::binary_search(row_keys_.begin(), row_keys_.end(), pair) ||
         std::binary_search(disabled_.begin(), disabled_.end(), pair);
}

std::span<const std::uint32_t> ShapeWorld::near_segments(const ShapeTick& tick, const Aabb& box) {
  near_segments_.clear();
  if (tick.segments.empty()) return {};
  tick.segment_grid->query(box.lower.x, box.lower.y, box.upper.x, box.upper.y, near_segments_);
  return near_segments_;
}

// From the broadphase's grid where it made one this tick (its boxes hold the shapes' at the
// start, grown by a margin), else every static body's; in the order of the static bodies and
// their shapes (shapes_ holds each body's shapes together, in body order: ascending indices),
// so that each time of impact is bounded by the same earlier ones.
std::span<const std::uint32_t> ShapeWorld::static_shapes_near(const Aabb& box) {
  near_statics_.clear();
  if (rest_.split) {  // the resting grid holds every static shape but the sensors
    const SweptBox q{box.lower.x, box.lower.y, box.upper.x, box.upper.y};
    rest_.grid.query(q, [&](std::uint32_t g, const SweptBox&) {
      const std::uint32_t k = rest_.resting[g];
      if (bodies_[shapes_[k].owner].type == BodyType::static_body) near_statics_.push_back(k);
    });
    std::sort(near_statics_.begin(), near_statics_.end());
    return near_statics_;
  }
  for (const std::uint32_t o : rest_.statics) {
    for (std::uint32_t q = bodies_[o].first; q < bodies_[o].first + bodies_[o].count; ++q) {
      near_statics_.push_back(q);
    }
  }
  return near_statics_;
}

double ShapeWorld::first_static_touch(std::uint32_t body, const ShapeTick& tick) {
  const ShapedBody& b = bodies_[body];
  const ShapeState& s = state_[body];
  const Sweep sweep{{s.x0, s.y0}, {s.x, s.y}, s.a0, s.a};
  const Pose start = start_pose(body);
  const double target = slop;
  double first = 1.0;
  for (std::uint32_t k = b.first; k < b.first + b.count; ++k) {
    const ShapeEntry& e = shapes_[k];
    if (e.sensor) continue;
    const Aabb swept = merge(convex_aabb(e.convex, start), convex_aabb(e.convex, pose(body)));
    for (std::uint32_t p = 0; p < tick.planes.size(); ++p) {
      if (has_row(std::uint64_t{0xF0000000u | p} << 32 | e.key)) continue;
      const PlaneDef& pl = tick.planes[p];
      const double len = det::hypot(pl.normal.x, pl.normal.y);
      const Vec2 n = pl.normal / len;
      const double off = pl.offset / len;
      if (plane_distance(n, off, e.convex, start) < 2.0 * target) continue;  // resting on it
      const double t = plane_toi(n, off, e.convex, sweep, target);
      if (e.one_way && t < 1.0 && !(dot(-n, rotate(pose_at(sweep, t).q, e.up)) > one_way_min_dot)) {
        continue;  // its one-way shape meets the plane from below: passes
      }
      first = std::min(first, t);
    }
    for (const std::uint32_t q : near_segments(tick, swept)) {
      const SegmentDef& seg = tick.segments[q];
      if (!boxes_overlap(swept, segment_bounds(seg))) continue;
      if (has_row(std::uint64_t{0xE0000000u | q} << 32 | e.key)) continue;
      const Convex c = segment_convex(seg.a, seg.b);
      const Sweep still{{0, 0}, {0, 0}, 0, 0};
      if (distance(c, Pose{}, e.convex, start).distance < 2.0 * target) continue;
      const Toi toi = time_of_impact(c, still, e.convex, sweep, target, 0.25 * target, first);
      if (!toi.hit) continue;
      if (seg.one_way || e.one_way) {  // the first touch must lean up for each one-way side
        const Pose hit = pose_at(sweep, toi.t);
        const Manifold m = collide_segment(seg, e.convex, hit, 4.0 * slop);
        if (seg.one_way && !one_way_touch(m, one_way_up_of(seg))) continue;
        if (e.one_way && !one_way_touch(m, -rotate(hit.q, e.up))) continue;
      }
      first = std::min(first, toi.t);
    }
    for (const std::uint32_t q : static_shapes_near(swept)) {
      const ShapeEntry& f = shapes_[q];
      const std::uint32_t o = f.owner;
      const Pose at = pose(o);
      const Sweep still{{at.p.x, at.p.y}, {at.p.x, at.p.y}, state_[o].a, state_[o].a};
      if (f.sensor || !should_collide(e.filter, f.filter)) continue;
      if (!boxes_overlap(swept, convex_aabb(f.convex, at))) continue;
      const std::uint32_t lo = std::min(q, k), hi = std::max(q, k);
      if (has_row(std::uint64_t{shapes_[lo].key} << 32 | shapes_[hi].key)) continue;
      if (distance(f.convex, at, e.convex, start).distance < 2.0 * target) continue;
      const Toi toi =
          time_of_impact(f.convex, still, e.convex, sweep, target, 0.25 * target, first);
      if (!toi.hit) continue;
      if (f.one_way || e.one_way) {  // the first touch must lean up for each one-way side
        const Pose hit = pose_at(sweep, toi.t);
        const Manifold m = collide(f.convex, at, e.convex, hit, 4.0 * slop);
        if (f.one_way && !one_way_touch(m, rotate(at.q, f.up))) continue;
        if (e.one_way && !one_way_touch(m, -rotate(hit.q, e.up))) continue;
      }
      first = std::min(first, toi.t);
    }
  }
  return first;
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

bool ShapeWorld::unpaired(std::uint32_t a, std::uint32_t b) const {
  const std::uint64_t key = std::uint64_t{std::min(a, b)} << 32 | std::max(a, b);
  return std::binary_search(unpaired_.begin(), unpaired_.end(), key);
}

bool ShapeWorld::moving(std::uint32_t body) const {
  const ShapedBody& b = bodies_[body];
  if (b.type != BodyType::kinematic) return awake(b);
  const ShapeState& s = state_[body];
  return s.vx != 0.0 || s.vy != 0.0 || s.w != 0.0;
}

ShapeTally ShapeWorld::solve(const ShapeTick& tick) {
  ShapeTally tally;
  joints_ = tick.joints, unpaired_ = tick.unpaired;
  visited_ = rest_.stale ? bodies_.size() : rest_.live.size();
  joints_visited_ = 0;
  if (rest_.stale) {
    rebuild_rest(tick.dt);
  } else {
    for (const std::uint32_t i : rest_.live) state_[i].q0 = rot_of(state_[i].a0);
  }
  // The second thread, with two: the discs' where its run is open, else the shape world's
  // own. A large world makes its broadphase and manifolds by halves on it (the run keeps the
  // worker spinning through the shape phase); the velocity sweeps split their large colours.
  SecondThread* const second = tick.threads < 2         ? nullptr
                               : tick.thread != nullptr ? tick.thread
                                                        : &second_;
  SecondThread* const thread = shapes_.size() >= min_split_shapes ? second : nullptr;
  const SecondThreadRun team(thread);
  halved_ = thread != nullptr;
  bool paired = broadphase(tick.dt, tally, thread);
  if (paired && !wake_.empty() && tick.wake) {  // sleepers woken: paired again as they now are
    tick.wake(tick.wake_context);
    if (rest_.stale) rebuild_rest(tick.dt), visited_ = bodies_.size();  // (the wake makes it so)
    paired = broadphase(tick.dt, tally, thread);
  }
  if (!paired) {  // a work limit: the tick's shape contacts unresolved
    rows_.clear(), kept_.clear();
    return tally;
  }
  collect(tick, thread);
  tally.pairs = candidates_.size();
  tally.points = rows_.size();
  prepare_rows(tick);
  joint_thread_ = second;  // the joints' passes by halves where prepare_joints splits them
  prepare_joints();
  const SecondThreadRun joints_team(joints_halved_ ? joint_thread_ : nullptr);
  tally.velocity_sweeps = solve_velocities(tick, second);
  follow_velocities();
  account_joints();
  continuous(tick, tally);
  solve_positions(tick, tally);
  keep_impulses();
  if (!sensor_candidates_.empty() || !sensed_.empty()) detect_sensors();
  throw_if_stop_requested();
  return tally;
}

}  // namespace fixstep::detail
