// Shape contacts, part 3: the push-out of the overlap left after the velocity solve, on
// positions only (non-linear Gauss-Seidel, Box2D v2.4's position solver), with the joints'
// errors; a large world's rows by halves (ShapeWorld::PushSplit).
#include <algorithm>
#include <array>
#include <limits>
#include <span>

#include "shape_world.hpp"

namespace fixstep::detail {

namespace {

/// Box2D v2.4's position solver: the fraction of the overlap beyond the slop one iteration
/// removes (b2_baumgarte) and the largest push of one point (b2_maxLinearCorrection, m).
constexpr double push_fraction = 0.2;
constexpr double max_push = 0.2;

}  // namespace

/// A row's push (Box2D v2.4's b2PositionSolverManifold over one point): its separation now,
/// from its manifold's at the start poses changed by how far each body's copy of the point has
/// moved since along the normal (the lever arm turned by the body's turn since the start).
struct ShapeWorld::Pusher {
  ShapeState* state;
  const ShapedBody* bodies;
  /// Per body: the evaluation (PushRow::idle's clock) that last moved it, 0 for none.
  std::uint64_t* moved_at;
  /// Whether rows are marked idle: only where nothing but the rows moves the bodies (no joint
  /// corrections between sweeps).
  bool track;

  [[nodiscard]] Vec2 moved(std::uint32_t body, Vec2 r) const {
    const ShapeState& s = state[body];
    const Vec2 now = Vec2{s.x - s.x0, s.y - s.y0} + rotate(s.turn, r);
    return now - r;
  }
  [[nodiscard]] double separation(const PushRow& r) const {
    Vec2 d = moved(r.b, r.rb);
    if (r.a != none) d = d - moved(r.a, r.ra);
    return r.separation + dot(d, r.n);
  }
  /// Pushes the row's bodies apart by its share of the overlap beyond the slop (evaluation
  /// `at`); whether it did.
  bool push(const PushRow& r, std::uint64_t at) const {
    const double c = std::clamp(push_fraction * (separation(r) + slop), -max_push, 0.0);
    if (c == 0.0 || r.normal_mass == 0.0) return false;
    const Vec2 p = (-c * r.normal_mass) * r.n;
    if (r.a != none && movable(bodies[r.a])) {
      const ShapedBody& b = bodies[r.a];
      ShapeState& s = state[r.a];
      s.x -= b.inv_mass * p.x, s.y -= b.inv_mass * p.y, s.a -= b.inv_inertia * cross(r.ra, p);
      moved_at[r.a] = at;
    }
    if (movable(bodies[r.b])) {
      const ShapedBody& b = bodies[r.b];
      ShapeState& s = state[r.b];
      s.x += b.inv_mass * p.x, s.y += b.inv_mass * p.y, s.a += b.inv_inertia * cross(r.rb, p);
      moved_at[r.b] = at;
    }
    return true;
  }
  /// Whether the row found nothing to push when last evaluated and neither body has moved
  /// since: its separation, and so its push of zero, would be the same.
  [[nodiscard]] bool unchanged(const PushRow& r) const {
    return r.idle != 0 && moved_at[r.b] < r.idle && (r.a == none || moved_at[r.a] < r.idle);
  }
  /// The row's push as evaluation `at`, marking it idle where it pushed nothing; whether it
  /// pushed.
  bool visit(PushRow& r, std::uint64_t at) const {
    if (push(r, at)) {
      r.idle = 0;
      return true;
    }
    if (track) r.idle = at;
    return false;
  }
};

void ShapeWorld::split_push_out(SecondThread* thread) {
  PushSplit& s = push_split_;
  s.on = false;
  if (rows_.size() < min_split_rows) return;
  // The live movable bodies' start positions: their extent on each axis and their mean.
  constexpr double inf = std::numeric_limits<double>::infinity();
  double lo_x = inf, hi_x = -inf, lo_y = inf, hi_y = -inf, sum_x = 0.0, sum_y = 0.0;
  std::size_t n = 0;
  for (const std::uint32_t k : rest_.live) {
    if (!movable(bodies_[k])) continue;
    const ShapeState& b = state_[k];
    lo_x = std::min(lo_x, b.x0), hi_x = std::max(hi_x, b.x0), sum_x += b.x0;
    lo_y = std::min(lo_y, b.y0), hi_y = std::max(hi_y, b.y0), sum_y += b.y0;
    ++n;
  }
  if (n < 2) return;
  const bool along_x = hi_x - lo_x >= hi_y - lo_y;
  const double line = (along_x ? sum_x : sum_y) / static_cast<double>(n);
  if (s.side.size() < bodies_.size()) s.side.resize(bodies_.size(), PushSplit::no_side);
  each_live(thread, [&](std::uint32_t k) {
    if (movable(bodies_[k])) s.side[k] = (along_x ? state_[k].x0 : state_[k].y0) < line ? 0 : 1;
  });
  // A row's part: the side of its movable bodies (0 with none), the cut where they differ or
  // one has no side.
  auto part = [&](const ShapeRow& r) -> std::uint8_t {
    std::uint8_t sa = PushSplit::any, sb = PushSplit::any;
    if (r.a != none && movable(bodies_[r.a])) sa = s.side[r.a];
    if (movable(bodies_[r.b])) sb = s.side[r.b];
    if (sa == PushSplit::any) sa = sb;
    if (sb == PushSplit::any) sb = sa;
    if (sa == PushSplit::any) return 0;
    return sa == sb && sa != PushSplit::no_side ? sa : 2;
  };
  // Each row's part, by halves of the rows on `thread`, each half counting its own.
  std::array<std::array<std::uint32_t, 3>, 2> counts{};
  s.part.resize(rows_.size());
  run_halves(thread, rows_.size(), [&](std::size_t begin, std::size_t end, int half) {
    for (std::size_t i = begin; i < end; ++i) {
      ++counts[static_cast<std::size_t>(half)][s.part[i] = part(rows_[i])];
    }
  });
  const std::array<std::uint32_t, 3> count{counts[0][0] + counts[1][0], counts[0][1] + counts[1][1],
                                           counts[0][2] + counts[1][2]};
  each_live(thread, [&](std::uint32_t k) { s.side[k] = PushSplit::no_side; });
  if (count[0] > 0 && count[1] > 0 && 4 * std::size_t{count[2]} <= rows_.size()) {
    s.ends = {count[0], count[0] + count[1]};
    s.on = true;
  }
}

void ShapeWorld::make_push_rows(SecondThread* thread) {
  PushSplit& s = push_split_;
  s.rows.resize(rows_.size());
  if (s.moved_at.size() < bodies_.size()) s.moved_at.resize(bodies_.size(), 0);
  auto copy = [&](std::size_t i, std::size_t j) {
    const ShapeRow& r = rows_[i];
    s.rows[j] = {r.a, r.b, r.n, r.ra, r.rb, r.separation, solve_[i].normal_mass};
  };
  if (!s.on) {
    for (std::size_t i = 0; i < rows_.size(); ++i) copy(i, i);
    return;
  }
  // Half 0's rows, then half 1's, then the cut's, each in row order: half 0's and the cut's
  // on this thread, half 1's on `thread` at once when given.
  auto fill = [&](int h) {
    std::array<std::size_t, 3> next{0, s.ends[0], s.ends[1]};
    for (std::size_t i = 0; i < rows_.size(); ++i) {
      const std::uint8_t part = s.part[i];
      if ((part == 1) == (h == 1)) copy(i, next[part]++);
    }
  };
  if (thread != nullptr) {
    thread->both(fill);
  } else {
    fill(0), fill(1);
  }
}

bool ShapeWorld::push_rows(std::size_t from, std::size_t to, std::uint64_t first, int part) {
  PushSplit& s = push_split_;
  const bool track = s.skip_idle && rest_.live_joints.empty();
  const Pusher pusher{state_.data(), bodies_.data(), s.moved_at.data(), track};
  PushRow* const rows = s.rows.data();
  bool pushed = false;
  std::uint64_t skipped = 0;
  for (std::size_t j = from; j < to; ++j) {
    if (pusher.unchanged(rows[j])) {
      ++skipped;
    } else {
      pushed |= pusher.visit(rows[j], first + j);
    }
  }
  s.skipped[static_cast<std::size_t>(part)] += skipped;
  return pushed;
}

bool ShapeWorld::push_sweep(SecondThread* thread) {
  // This sweep's evaluations are first + j for row j: after every earlier one.
  const std::uint64_t first = push_split_.clock + 1;
  push_split_.clock += rows_.size();
  if (!push_split_.on) return push_rows(0, rows_.size(), first, 0);
  // Each half's rows move only that half's bodies: on two threads at once or one after the
  // other, the same bits. Then the cut's, on this thread.
  const std::array<std::size_t, 2> ends = push_split_.ends;
  std::array<bool, 2> pushed{};
  auto half = [&](int h) { pushed[h] = push_rows(h == 0 ? 0 : ends[0], ends[h], first, h); };
  if (thread != nullptr) {
    thread->both(half);
    ++split_pushes_;
  } else {
    half(0), half(1);
  }
  const bool cut = push_rows(ends[1], rows_.size(), first, 2);
  return pushed[0] || pushed[1] || cut;
}

void ShapeWorld::update_turns(SecondThread* thread) {
  const std::span<const std::uint32_t> live = rest_.live;
  run_halves(thread, live.size(), [&](std::size_t begin, std::size_t end, int /*half*/) {
    RotBatch batch;  // (the rotations in batches: the same bits as rot_of)
    auto store = [&](std::uint32_t k, Rot q) { state_[k].turn = q; };
    for (std::size_t j = begin; j < end; ++j) {
      const std::uint32_t k = live[j];
      ShapeState& s = state_[k];
      if (s.a != turned_at_[k]) batch.add(k, s.a - s.a0, store), turned_at_[k] = s.a;
    }
    batch.flush(store);
  });
}

void ShapeWorld::solve_positions(const ShapeTick& tick, SecondThread* second, ShapeTally& tally) {
  // Each point's separation now: its manifold's (at the start poses) changed by how far each
  // body's copy of the point has moved since along the normal (the lever arm turned by the
  // body's turn since the start, made again only where its angle has changed since:
  // turned_at_ holds the angle it was made at, NaN at first, unequal to any; a resting body's
  // turn, none, is made by rebuild_rest).
  for (const std::uint32_t k : rest_.live) turned_at_[k] = std::numeric_limits<double>::quiet_NaN();
  // The joints' errors of this tick's motion first, as constraint impulses (they move the
  // velocities too), then every error left, the contacts' and the joints', on positions only.
  // A sweep that moves nothing leaves the poses as they were, and so would every sweep after
  // it: the sweeps have ended.
  const int keeping = std::max(tick.position_iterations, direct_position_steps);
  keep_search_.pending = false;  // (a tick that a stop request ended may have left one)
  for (int it = 0; it < keeping && !rest_.live_joints.empty(); ++it) {
    poll_stop();
    if (!solve_joint_positions(true)) break;
  }
  end_keeping();
  split_push_out(halved_ ? second : nullptr);
  SecondThread* const thread = push_split_.on ? second : nullptr;
  const SecondThreadRun team(thread);
  make_push_rows(thread);
  update_turns(thread);
  for (int it = 0; it < tick.position_iterations; ++it) {
    poll_stop();
    const bool pushed = push_sweep(thread);
    // A sweep that pushes and corrects nothing leaves the poses as they were, and so would
    // every sweep after it: the push-out has ended.
    if (!pushed && rest_.live_joints.empty()) break;
    const bool corrected = !rest_.live_joints.empty() && solve_joint_positions(false);
    if (!pushed && !corrected) break;
    update_turns(thread);
  }
  const Pusher pusher{state_.data(), bodies_.data(), nullptr, false};
  for (const PushRow& r : push_split_.rows) {
    tally.deepest = std::max(tally.deepest, -pusher.separation(r));
  }
  // (By halves where the shape phase's run holds the second thread: the same rotations.)
  rot_each_live(
      halved_ ? second : nullptr, [&](std::uint32_t k) { return state_[k].a; },
      [&](std::uint32_t k, Rot q) { state_[k].q = q; });
}

}  // namespace fixstep::detail
