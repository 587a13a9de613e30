// Shape contacts, part 2: the contact solver (shape_world.hpp has the whole tick): the impact
// pass (bounces), then sequential impulses with warm starting on the manifold points (the
// push-out of the overlap left, on positions only: shape_push_out.cpp).
#include <algorithm>
#include <array>
#include <cmath>

#include "shape_rows.hpp"
#include "shape_world.hpp"

namespace fixstep::detail {

using namespace shape_rows;

namespace {

Vec2 perp(Vec2 n) {
  return {-n.y, n.x};
}

/// std::lower_bound(first, last, key, less) over a range sorted by `less`, searched from `hint`
/// on by doubling steps when key is at or past *hint (else over the whole range): the same
/// element, in O(log d) for a key d places past the hint. `hint` must not be past the first
/// element equal to key (a lower bound of a key at or before this one is not).
template <class It, class T, class Less>
It lower_bound_from(It first, It last, It hint, const T& key, Less less) {
  It low = first, high = last;
  if (hint != last && !less(key, *hint)) {
    low = hint;
    for (std::ptrdiff_t step = 1; high - low > step; step *= 2) {
      if (!less(low[step], key)) {
        high = low + step;
        break;
      }
      low += step;
    }
  }
  return std::lower_bound(low, high, key, less);
}

bool pair_less(const ShapeWarm& l, const ShapeWarm& r) {
  return l.pair < r.pair;
}

}  // namespace

// A row's impulses change velocities only; the poses follow once, after the whole velocity
// solve (follow_velocities), by dt times each body's velocity change.
[[gnu::always_inline]] inline void ShapeWorld::apply(const ShapeSolveRow& h, double pn, double pt) {
  Motion2 m = load(h);
  push(h, pn, pt, m.a, m.b);
  store(h, m);
}

[[gnu::always_inline]] inline double ShapeWorld::normal_velocity(const ShapeSolveRow& h) const {
  const Motion2 m = load(h);
  return normal_of(h, m.a, m.b);
}

[[gnu::always_inline]] inline double ShapeWorld::tangent_velocity(const ShapeSolveRow& h) const {
  const Motion2 m = load(h);
  return tangent_of(h, m.a, m.b);
}

// Every field assigned, none cleared first: a row value-initialized and then assigned (or made
// by an initializer with fields left out) was cleared whole with a string instruction, per row.
// The rows are reused from tick to tick, so a field added to ShapeSolveRow must be assigned here
// too (the size below stops a build that forgets).
static_assert(sizeof(ShapeSolveRow) == 192, "make_solve_row assigns every field: add the new one");
[[gnu::always_inline]] inline void ShapeWorld::make_solve_row(const ShapeRow& r,
                                                              ShapeSolveRow& h) const {
  const Vec2 t = perp(r.n);
  const double rna = cross(r.ra, r.n), rnb = cross(r.rb, r.n);
  const double rta = cross(r.ra, t), rtb = cross(r.rb, t);
  const double ma = r.a != none ? bodies_[r.a].inv_mass : 0.0;
  const double ia = r.a != none ? bodies_[r.a].inv_inertia : 0.0;
  const double mb = bodies_[r.b].inv_mass, ib = bodies_[r.b].inv_inertia;
  const double kn = ma + mb + ia * rna * rna + ib * rnb * rnb;
  const double kt = ma + mb + ia * rta * rta + ib * rtb * rtb;
  h.a = r.a, h.b = r.b, h.flags = 0, h.nx = r.n.x, h.ny = r.n.y;
  h.rna = rna, h.rnb = rnb, h.rta = rta, h.rtb = rtb;
  h.ma = ma, h.ia = ia, h.mb = mb, h.ib = ib, h.kn = kn, h.kt = kt;
  h.normal_mass = kn > 0.0 ? 1.0 / kn : 0.0;
  h.tangent_mass = kt > 0.0 ? 1.0 / kt : 0.0;
  h.k12 = 0.0, h.target = 0.0, h.block_mass = {0.0, 0.0, 0.0};
  h.friction = r.friction, h.ln = 0.0, h.lt = 0.0;
}

void ShapeWorld::prepare_rows(const ShapeTick& tick, SecondThread* thread) {
  // By halves on `thread` in a large world: the live bodies' velocities (velocity_ has a slot
  // for each body and the zero slot; a resting body's holds its velocity, none, from
  // rebuild_rest on), then each row's own and each manifold's block, the halves cut between
  // two manifolds.
  const std::size_t parts = thread != nullptr && rows_.size() >= min_split_rows ? 2 : 1;
  each_live(parts == 2 ? thread : nullptr, [&](std::uint32_t k) {
    velocity_[k] = {state_[k].vx, state_[k].vy, state_[k].w};
  });
  velocity_[zero_slot()] = {};
  solve_.resize(rows_.size());
  std::size_t cut = rows_.size() / 2;
  if (cut > 0 && pairs_next(cut - 1)) ++cut;  // a manifold has at most two rows
  const std::array<std::size_t, 3> ends{0, parts == 2 ? cut : rows_.size(), rows_.size()};
  std::array<bool, 2> bounces{};  // whether each part has a row with restitution
  auto make = [&](int part) {
    const auto p = static_cast<std::size_t>(part);
    bool any = false;
    for (std::size_t i = ends[p]; i < ends[p + 1]; ++i) {
      ShapeRow& r = rows_[i];
      ShapeSolveRow& h = solve_[i];
      make_solve_row(r, h);
      r.rolling_mass = r.rolling > 0.0 && h.ia + h.ib > 0.0 ? 1.0 / (h.ia + h.ib) : 0.0;
      r.lr = 0.0;
      // The normal velocity the row asks for: a gap may close within the tick, a touching
      // point stops approaching (the bounces are the impact pass's).
      r.approach = std::max(-normal_velocity(h), 0.0);
      h.target = r.separation > 0.0 ? -r.separation / tick.dt : 0.0;
      r.bn = 0.0, r.bt = 0.0;
      any = any || r.restitution > 0.0;
    }
    prepare_blocks(ends[p], ends[p + 1]);
    bounces[p] = any;
  };
  if (parts == 2) {
    thread->both(make);
  } else {
    make(0);
  }
  // (Without restitution no point bounces: the pass would find none.)
  for (int pass = 0; pass < max_impact_passes && (bounces[0] || bounces[1]) && impact_pass(tick);
       ++pass) {
  }
  // Warm starting, once every row's target is set from the free velocities. The rows come
  // mostly in pair order: each search starts where the last one ended, and finds the point
  // among its pair's (warm_ is sorted by pair, keep_impulses). `after` is the first entry of
  // the last row's pair, or where it would be; `next` follows the last entry taken. Most rows
  // are last tick's in its order, so the first entry of a row's pair is most often one of
  // those two, known without a search.
  const auto begin = warm_.begin(), end = warm_.end();
  auto after = begin, next = begin;
  for (std::size_t i = 0; i < rows_.size(); ++i) {
    ShapeRow& r = rows_[i];
    ShapeSolveRow& h = solve_[i];
    if (h.flags & ShapeSolveRow::redundant) continue;
    if (next != end && next->pair == r.pair && (next == begin || next[-1].pair < r.pair)) {
      after = next;
    } else if (after == end || after->pair != r.pair) {
      after = lower_bound_from(begin, end, after, ShapeWarm{r.pair, r.id}, pair_less);
    }
    for (auto warm = after; warm != end && warm->pair == r.pair; ++warm) {
      if (warm->id != r.id) continue;
      next = warm + 1;
      h.ln = warm->ln, h.lt = warm->lt;
      apply(h, h.ln, h.lt);
      if (r.rolling_mass > 0.0) r.lr = warm->lr, turn(r, r.lr);
      break;
    }
  }
}

// Impacts, before the resting solve: every point that meets within the tick faster than the
// restitution threshold, at the velocities the bounces before it left, gets the impulse that
// gives it −e times its normal velocity (Newton's law; a manifold's two points together), and
// the Coulomb-bounded tangential impulse that stops its sliding. Each bounce is a collision of
// two bodies at one point (or one edge) that keeps their momentum and angular momentum, and
// their energy when e = 1 and μ = 0: a body that meets two others within one tick bounces off
// both in turn, as Guendelman, Bridson and Fedkiw's collision pass does (SIGGRAPH 2003), where
// the resting solve alone would stop it at the second without a bounce. The passes end when no
// point meets (bounded by max_impact_passes; what is left is stopped by the resting solve).
bool ShapeWorld::impact_pass(const ShapeTick& tick) {
  bool any = false;
  for (std::size_t i = 0; i < rows_.size(); ++i) {
    const std::uint8_t flags = solve_[i].flags;
    if (flags & ShapeSolveRow::block_first) {
      any = bounce_block(i, tick) || any;
      ++i;
    } else if (!(flags & ShapeSolveRow::redundant)) {
      any = bounce(i, tick) || any;
    }
  }
  return any;
}

namespace {

/// Whether a point of separation s (m) and normal velocity vn (m/s) meets within the tick dt
/// fast enough to bounce.
bool meets(const ShapeRow& r, double vn, const ShapeTick& tick) {
  // (the threshold is >= 0, so a point that meets approaches)
  return r.restitution > 0.0 && vn < -tick.restitution_threshold &&
         r.separation + vn * tick.dt < 0.0;
}

}  // namespace

bool ShapeWorld::bounce(std::size_t i, const ShapeTick& tick) {
  ShapeRow& r = rows_[i];
  if (!(r.restitution > 0.0)) return false;  // meets() never holds: no velocity to load
  const ShapeSolveRow& h = solve_[i];
  const double vn = normal_velocity(h);
  if (!meets(r, vn, tick)) return false;
  const double pn = -(1.0 + r.restitution) * vn * h.normal_mass;
  const double vt = tangent_velocity(h);
  const double pt = std::clamp(-vt * h.tangent_mass, -r.friction * pn, r.friction * pn);
  r.bn += pn, r.bt += pt;
  apply(h, pn, pt);
  return true;
}

// A manifold's two points meeting at once: the 2×2 problem K x = −(1 + e) vn for the points
// that meet (x >= 0; a point that would pull is left out and the other solved alone).
bool ShapeWorld::bounce_block(std::size_t i, const ShapeTick& tick) {
  ShapeRow &r1 = rows_[i], &r2 = rows_[i + 1];
  if (!(r1.restitution > 0.0) && !(r2.restitution > 0.0)) return false;  // as bounce()
  const ShapeSolveRow &h1 = solve_[i], &h2 = solve_[i + 1];
  const double vn1 = normal_velocity(h1), vn2 = normal_velocity(h2);
  const bool m1 = meets(r1, vn1, tick), m2 = meets(r2, vn2, tick);
  if (!m1 && !m2) return false;
  const double k11 = h1.kn, k22 = h2.kn, k12 = h1.k12;
  const double d1 = m1 ? -(1.0 + r1.restitution) * vn1 : 0.0;
  const double d2 = m2 ? -(1.0 + r2.restitution) * vn2 : 0.0;
  double x1 = 0.0, x2 = 0.0;
  const double det = k11 * k22 - k12 * k12;
  if (m1 && m2) x1 = (k22 * d1 - k12 * d2) / det, x2 = (k11 * d2 - k12 * d1) / det;
  if (!(m1 && m2 && x1 >= 0.0 && x2 >= 0.0)) {  // one point alone: the one that meets
    const bool first = m1 && (!m2 || d1 / k11 >= d2 / k22);
    x1 = first ? d1 / k11 : 0.0, x2 = first ? 0.0 : d2 / k22;
  }
  r1.bn += x1, r2.bn += x2;
  if (x1 != 0.0) apply(h1, x1, 0.0);
  if (x2 != 0.0) apply(h2, x2, 0.0);
  for (int k = 0; k < 2; ++k) {  // sliding stopped within each point's Coulomb cone
    ShapeRow& r = k == 0 ? r1 : r2;
    const ShapeSolveRow& h = k == 0 ? h1 : h2;
    const double bound = r.friction * (k == 0 ? x1 : x2);
    if (bound == 0.0) continue;
    const double pt = std::clamp(-tangent_velocity(h) * h.tangent_mass, -bound, bound);
    r.bt += pt;
    apply(h, 0.0, pt);
  }
  return true;
}

void ShapeWorld::prepare_blocks(std::size_t begin, std::size_t end) {
  for (std::size_t i = begin; i + 1 < end; ++i) {
    if (!pairs_next(i)) continue;
    const ShapeRow& r1 = rows_[i];
    const ShapeRow& r2 = rows_[i + 1];
    ShapeSolveRow &h1 = solve_[i], &h2 = solve_[i + 1];
    if (r1.rolling > 0.0) h1.flags |= ShapeSolveRow::rolls_pair;
    if (h1.normal_mass == 0.0 || h2.normal_mass == 0.0) continue;
    const double k12 = h1.ma + h1.mb + h1.ia * h1.rna * h2.rna + h1.ib * h1.rnb * h2.rnb;
    const double k11 = h1.kn, k22 = h2.kn;
    // Box2D's condition number guard: a K this close to singular keeps one point (the deeper).
    if (k11 * k11 < 1000.0 * (k11 * k22 - k12 * k12)) {
      const double det = k11 * k22 - k12 * k12;
      h1.flags |= ShapeSolveRow::block_first, h1.k12 = k12;
      h1.block_mass = {k22 / det, -k12 / det, k11 / det};
    } else {
      (r2.separation < r1.separation ? h1 : h2).flags |= ShapeSolveRow::redundant;
    }
    ++i;
  }
  for (std::size_t i = begin; i < end; ++i) {
    if (rows_[i].rolling_mass > 0.0) solve_[i].flags |= ShapeSolveRow::rolls;
  }
}

// Rolling resistance (Box2D v3.1's b2SolveContact): an angular impulse that stops the two
// bodies' relative turning, within ± c r times the manifold's normal impulse. Returns the
// change of the relative turning rate it made (rad/s).
double ShapeWorld::solve_rolling(ShapeRow& r, double normal_impulse) {
  const double wa = r.a != none ? velocity_[r.a].w : 0.0;
  const double bound = std::max(r.rolling * normal_impulse, 0.0);  // as solve_friction's
  const double lr = std::clamp(r.lr - r.rolling_mass * (velocity_[r.b].w - wa), -bound, bound);
  const double d = lr - r.lr;
  r.lr = lr;
  if (d != 0.0) turn(r, d);
  return r.rolling_mass > 0.0 ? std::abs(d) / r.rolling_mass : 0.0;
}

void ShapeWorld::turn(const ShapeRow& r, double l) {
  if (r.a != none && bodies_[r.a].inv_inertia > 0.0)
    velocity_[r.a].w -= bodies_[r.a].inv_inertia * l;
  if (bodies_[r.b].inv_inertia > 0.0) velocity_[r.b].w += bodies_[r.b].inv_inertia * l;
}

void ShapeWorld::follow_velocities() {
  for (const std::uint32_t k : rest_.live) {
    ShapeState& s = state_[k];  // its velocities still the free ones
    const ShapeMotion& v = velocity_[k];
    s.x += dt_ * (v.vx - s.vx), s.y += dt_ * (v.vy - s.vy), s.a += dt_ * (v.w - s.w);
    s.vx = v.vx, s.vy = v.vy, s.w = v.w;
  }
}

void ShapeWorld::keep_impulses() {
  next_warm_.clear();
  for (const ShapeRow& r : rows_) {
    if (r.ln != 0.0 || r.lt != 0.0 || r.lr != 0.0) {
      next_warm_.push_back({r.pair, r.id, r.ln, r.lt, r.lr});
    }
  }
  // Sorted by pair, a pair's points in any order (prepare_rows looks for a point among its
  // pair's). The rows come in pair order unless destroyed slots were reused, or a shape touches
  // more than one plane or segment (the surfaces' rows come last, shape by shape): then only
  // what follows the sorted start's last entry not past the rest's least is sorted.
  const auto begin = next_warm_.begin(), end = next_warm_.end();
  const auto rest = std::is_sorted_until(begin, end, pair_less);
  if (rest != end) {
    const ShapeWarm least = *std::min_element(rest, end, pair_less);
    std::sort(std::upper_bound(begin, rest, least, pair_less), end);
  }
  warm_.swap(next_warm_);
}

}  // namespace fixstep::detail
