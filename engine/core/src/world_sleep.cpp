// Sleeping islands (ContactSettings::sleep): bodies at rest that cost nothing until something
// comes near, as Box2D's islands sleep (Catto, "Solver2D" and b2_timeToSleep: bodies slower
// than 5 cm/s for 0.5 s).
//
// At the end of a tick every dynamic disc that moves slower than sleep_speed (its centre, and
// with rolling discs its rim) counts one more still tick, any other body none. Islands are the
// awake bodies joined by the tick's resting contacts between dynamic discs and by links
// (union-find, the smaller index the root). An island sleeps when every body in it is a
// dynamic disc (not a sensor) that has been still for sleep_ticks_ ticks, none had input,
// and none touches or is linked to a kinematic body that moves; its velocities become 0 (the
// kinetic energy they held goes to the dissipated account), it joins the immovable bodies
// (put back after each free step) and the disc phases see it as a static disc.
//
// An island wakes, whole, when the swept box of an awake disc's motion over a tick (the box the
// broadphase pairs it by, after the plane contacts) overlaps the box of one of its discs (the
// disc padded as the broadphase pads it): DiscContacts::resolve calls wake_near_movers() once
// the boxes are built and before they are paired, so the broadphase never pairs an awake disc
// with a sleeper, and the woken bodies take part in the tick's impacts and resting contacts from
// rest where they slept. Islands are joined over the candidate pairs as well as the resting
// contacts, so two islands that the broadphase pairs never wake each other in turn. An island
// also wakes on input to one of its bodies, on an edit of one (set_position, set_velocity,
// World::wake), and, as a check that should never fire, when an impact or resting contact with
// an awake disc reached it (ContactStats::sleeper_contacts). A structural change (a body,
// component, link or plane created or destroyed, set_body) wakes every island.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "disc_contacts.hpp"
#include "island_union.hpp"
#include "shape_world.hpp"
#include "sorted_lists.hpp"
#include "world_kernel.hpp"

namespace fixstep {

namespace {

constexpr std::uint32_t still_cap = 0xffffffffu;  // a saturating count of still ticks

}  // namespace

template <class Real>
std::uint32_t detail::WorldKernel<Real>::sleep_ticks(const ContactSettings& c, double dt) {
  if (!std::isfinite(c.sleep_speed) || c.sleep_speed <= 0.0) {
    throw std::invalid_argument(fmt::format(
        "world: contacts.sleep_speed must be finite and > 0 m/s (got {})", c.sleep_speed));
  }
  const double ticks = std::ceil(c.sleep_time / dt);
  if (!std::isfinite(c.sleep_time) || c.sleep_time < 0.0 || !(ticks < 1e9)) {
    throw std::invalid_argument(fmt::format(
        "world: contacts.sleep_time must be finite, >= 0 s and under 1e9 ticks (got {} s)",
        c.sleep_time));
  }
  return std::max(static_cast<std::uint32_t>(ticks), std::uint32_t{1});
}

template <class Real>
void detail::WorldKernel<Real>::reset_sleep() {
  const std::size_t n = body_count();
  still_ticks_.assign(n, 0);
  asleep_.assign(n, 0);
  island_next_.assign(n, 0);
  sleepers_ = 0, disc_sleepers_ = 0, shape_sleepers_ = 0;
  awake_.flipped.clear(), awake_.whole = true;
  asleep_pairs_stale_ = true;
  unsettle_shapes();
}

template <class Real>
bool detail::WorldKernel<Real>::mark_awake(std::size_t index) {
  if (!still_ticks_.empty()) still_ticks_[index] = 0;
  // After a structural change the rebuild at the next step wakes every island anyway.
  if (asleep_.empty() || asleep_[index] == 0 || terms_dirty_) return false;
  wake_bodies_.push_back(static_cast<std::uint32_t>(index));
  return true;
}

template <class Real>
void detail::WorldKernel<Real>::wake(std::size_t index) {
  if (mark_awake(index)) wake_labelled();
}

template <class Real>
void detail::WorldKernel<Real>::wake_labelled() {
  if (wake_bodies_.empty()) return;
  std::vector<std::uint32_t>& woken = flip_scratch_;
  woken.clear();
  for (const std::uint32_t b : wake_bodies_) {
    if (asleep_[b] == 0) continue;  // awake, or its island woken already
    ++woken_;
    std::uint32_t j = b;
    do {
      asleep_[j] = 0, woken.push_back(j);
      j = island_next_[j];
    } while (j != b);
  }
  wake_bodies_.clear();
  std::sort(woken.begin(), woken.end());  // in increasing order, as a pass over the bodies
  for (const std::uint32_t j : woken) {
    still_ticks_[j] = 0, --sleepers_;
    flip_sleep(j);
    if (shape_world_) shape_world_->unsettle_body(j);
    if (!shaped_dynamic_.empty() && shaped_dynamic_[j] != 0) --shape_sleepers_;
    const std::int32_t k = disc_of_.empty() ? -1 : disc_of_[j];
    if (k < 0) continue;  // a body with shapes: mark_shape_sleepers sets its masses back
    const double inv_i = rolling_ ? inv_inertia_[j] : 0.0;
    discs_->set_asleep(static_cast<std::uint32_t>(k), false, 1.0 / mass_[j], inv_i);
    --disc_sleepers_;
  }
  immovable_dirty_ = true;
  asleep_pairs_stale_ = true;  // their touching pairs go back to the per-tick lists
}

template <class Real>
void detail::WorldKernel<Real>::flip_sleep(std::uint32_t j) {
  AwakeRuns& a = awake_;
  if (a.whole) return;
  if (a.flipped.size() >= asleep_.size()) {
    a.flipped.clear(), a.whole = true;
    return;
  }
  a.flipped.push_back(j);
}

template <class Real>
template <class F>
void detail::WorldKernel<Real>::for_each_awake_body(F&& f) {
  const AwakeRuns& a = awake_;
  if (!a.on || a.whole) {
    for (std::uint32_t j = 0; j < asleep_.size(); ++j) {
      if (asleep_[j] == 0) f(j);
    }
    return;
  }
  // The runs as they were built, and the bodies flipped since (those woken are in no run).
  std::vector<std::uint32_t>& flipped = awake_.flipped;
  sort_unique(flipped);
  std::size_t x = 0;
  auto flipped_before = [&](std::uint32_t i) {
    for (; x < flipped.size() && flipped[x] < i; ++x) {
      if (asleep_[flipped[x]] == 0) f(flipped[x]);
    }
  };
  for (const IndexRun& r : a.bodies) {
    flipped_before(r.begin);
    for (std::uint32_t j = r.begin; j < r.end; ++j) {
      if (x < flipped.size() && flipped[x] == j) ++x;  // in a run: met here
      if (asleep_[j] == 0) f(j);
    }
  }
  flipped_before(0xffffffffu);
}

template <class Real>
void detail::WorldKernel<Real>::wake_for_input(const TickInput& input) {
  if (input.push.x != 0.0 || input.push.y != 0.0) {  // a push moves every body
    for (std::uint32_t j = 0; j < asleep_.size(); ++j) {
      if (asleep_[j] != 0) wake_bodies_.push_back(j);
    }
  }
  for (const BodyInput& b : input.bodies) {  // marked, then woken in one pass
    if (bodies_.contains(b.body)) mark_awake(bodies_.index(b.body));
  }
  if (bodies_.contains(input.drag_body)) mark_awake(bodies_.index(input.drag_body));
  for (const JointInput& in : input.joints) {  // a joint's input wakes both its bodies
    if (!contains(in.joint)) continue;
    const JointDef& def = joint(in.joint);
    for (const Entity e : {def.body_a, def.body_b}) {
      if (!e.is_null()) mark_awake(bodies_.index(e));
    }
  }
  wake_labelled();
}

template <class Real>
void detail::WorldKernel<Real>::wake_by_segments() {
  // A segment a kinematic body carries sweeps, this tick, the box of where place_segments() put
  // it and where it will be after dt: an island it may reach wakes before the free step.
  if (!discs_) return;  // no disc, so no disc sleeps
  const auto discs = discs_->discs();
  const double dt = settings_.dt;
  for (const std::uint32_t i : segments_.carried()) {
    const Vec2 u = segments_.velocity(i);
    if (u.x == 0.0 && u.y == 0.0) continue;
    const SegmentDef& s = segments_.defs()[i];
    const double x0 = std::min(s.a.x, s.b.x), x1 = std::max(s.a.x, s.b.x);
    const double y0 = std::min(s.a.y, s.b.y), y1 = std::max(s.a.y, s.b.y);
    const double lx = std::min(x0, x0 + u.x * dt), hx = std::max(x1, x1 + u.x * dt);
    const double ly = std::min(y0, y0 + u.y * dt), hy = std::max(y1, y1 + u.y * dt);
    const SweptBox swept{lx, ly, hx, hy};
    discs_->for_each_sleeper_near(x_.data(), y_.data(), swept, [&](std::uint32_t k) {
      const std::uint32_t j = discs[k].body;
      const double x = double(x_[j]), y = double(y_[j]);
      const double r = DiscContacts<Real>::box_pad(discs[k]);
      if (!boxes_overlap(SweptBox{x - r, y - r, x + r, y + r}, swept)) return;
      if (asleep_[j] != 0) wake_bodies_.push_back(j);
    });
  }
  wake_labelled();
}

template <class Real>
void detail::WorldKernel<Real>::wake_near_movers() {
  const auto discs = discs_->discs();
  const auto boxes = discs_->boxes();
  for (const std::uint32_t k : discs_->awake()) {
    const std::uint32_t j = discs[k].body;
    if (asleep_[j] != 0 || types_[j] == BodyType::static_body || discs[k].sensor) continue;
    const SweptBox& b = boxes[k];
    const auto mover = static_cast<std::uint32_t>(k);
    discs_->for_each_sleeper_near(x_.data(), y_.data(), b, [&](std::uint32_t other) {
      const std::uint32_t sleeper = discs[other].body;
      if (asleep_[sleeper] == 0 || !boxes_overlap(b, boxes[other])) return;
      if (!discs_->may_collide(mover, other)) return;
      wake_bodies_.push_back(sleeper);
    });
  }
  wake_labelled();
}

template <class Real>
bool detail::WorldKernel<Real>::discs_at_rest() const {
  if (disc_sleepers_ < dynamic_discs_) return false;
  return std::all_of(kinematic_discs_.begin(), kinematic_discs_.end(),
                     [&](std::uint32_t j) { return vx_[j] == Real(0) && vy_[j] == Real(0); });
}

template <class Real>
void detail::WorldKernel<Real>::quiet_discs() {
  begun_.clear(), ended_.clear(), hits_.clear(), impacts_.clear();
  sensor_begun_.clear(), sensor_ended_.clear();
  contact_stats_ = ContactStats{};
  profile_ = StepProfile{};
}

template <class Real>
void detail::WorldKernel<Real>::join_islands() {
  const std::size_t n = body_count();
  island_parent_.resize(n), island_blocked_.resize(n, 0);
  if (++blocked_stamp_ == 0) {  // the stamps wrapped: every entry is older than the next one
    std::fill(island_blocked_.begin(), island_blocked_.end(), 0u);
    blocked_stamp_ = 1;
  }
  for_each_awake_body([&](std::uint32_t j) { island_parent_[j] = j; });
  const std::uint32_t stamp = blocked_stamp_;
  std::vector<std::uint32_t>& blocked = island_blocked_;
  if (shape_world_) join_shape_islands();  // world_shape_sleep.cpp
  const auto discs = discs_ ? discs_->discs() : std::span<const Disc>{};
  auto moving = [&](std::uint32_t j) {
    return types_[j] == BodyType::kinematic && (vx_[j] != Real(0) || vy_[j] != Real(0));
  };
  // Two awake dynamic bodies: a sleeper near an awake island stays an island of its own.
  auto awake = [&](std::uint32_t j) { return types_[j] == BodyType::dynamic && asleep_[j] == 0; };
  // The touching disc pairs by their bodies (8 bytes a pair, not the contacts).
  const auto pair_bodies = discs_ ? discs_->touching_bodies() : std::span<const DiscPair>{};
  for (const DiscPair& p : pair_bodies) {
    const std::uint32_t a = p.a, b = p.b;
    const bool da = awake(a), db = awake(b);
    if (da && db) detail::join(island_parent_, a, b);
    if (da && moving(b)) blocked[a] = stamp;
    if (db && moving(a)) blocked[b] = stamp;
  }
  // The planes' and segments' contacts: a wall is static, unless a kinematic body's segment.
  const auto on_moving = discs_ ? discs_->on_moving_segment() : std::span<const std::uint32_t>{};
  for (const std::uint32_t k : on_moving) blocked[discs[k].body] = stamp;
  // Discs near enough to be paired by the broadphase share an island too: an awake one would
  // otherwise wake a sleeping neighbour every tick (Box2D links islands through contacts
  // within its speculative distance for the same reason).
  const auto pairs = discs_ ? discs_->candidate_pairs() : std::span<const DiscPair>{};
  for (const DiscPair& p : pairs) {
    const std::uint32_t a = discs[p.a].body, b = discs[p.b].body;
    if (awake(a) && awake(b)) detail::join(island_parent_, a, b);
  }
  for (std::size_t l = 0; l < net_.a.size(); ++l) {
    const std::uint32_t a = net_.a[l], b = net_.b[l];
    const bool da = awake(a), db = awake(b);
    if (da && db) detail::join(island_parent_, a, b);
    if (da && moving(b)) blocked[a] = stamp;
    if (db && moving(a)) blocked[b] = stamp;
  }
  for_each_awake_body([&](std::uint32_t j) {  // one not ready, or blocked, keeps its island up
    const bool ready = still_ticks_[j] >= sleep_ticks_;
    if (!ready || blocked[j] == stamp) blocked[detail::find_root(island_parent_, j)] = stamp;
  });
}

template <class Real>
void detail::WorldKernel<Real>::fall_asleep(std::size_t j, std::uint32_t label) {
  const double v2 = double(vx_[j]) * double(vx_[j]) + double(vy_[j]) * double(vy_[j]);
  double joules_per_kg = 0.5 * v2;
  if (rolling_ && inv_inertia_[j] > 0.0) {
    const double w = double(spin_[j]);
    joules_per_kg += 0.5 * w * w / (inv_inertia_[j] * mass_[j]);
    spin_[j] = Real(0);
  }
  const std::int32_t disc = disc_of_.empty() ? -1 : disc_of_[j];
  if (disc < 0) {  // a body with shapes: its turn stops too
    ShapeSet& set = shape_sets_.data[shape_sets_.set.index(bodies_.dense[j])];
    joules_per_kg += 0.5 * set.inertia * set.spin * set.spin / mass_[j];
    set.spin = 0.0;
  }
  if (settings_.track_dissipation) dissipated_body_[j] += static_cast<Real>(joules_per_kg);
  vx_[j] = Real(0), vy_[j] = Real(0);
  asleep_[j] = label, ++sleepers_;
  flip_sleep(static_cast<std::uint32_t>(j));
  if (shape_world_) shape_world_->unsettle_body(static_cast<std::uint32_t>(j));
  if (!shaped_dynamic_.empty() && shaped_dynamic_[j] != 0) ++shape_sleepers_;
  if (disc >= 0)
    discs_->set_asleep(static_cast<std::uint32_t>(disc), true, 0.0, 0.0), ++disc_sleepers_;
}

template <class Real>
std::uint32_t detail::WorldKernel<Real>::take_island_number() {
  // Numbers wrap after 2^32 - 1 islands (0 means awake and is skipped): two islands may then
  // share a number, which is safe: an island wakes round its ring (island_next_), not by its
  // number.
  const std::uint32_t n = next_island_;
  next_island_ = n == 0xffffffffu ? 1u : n + 1u;
  return n;
}

template <class Real>
void detail::WorldKernel<Real>::update_sleep(const TickInput& input, bool disc_phases) {
  const auto discs = disc_phases ? discs_->discs() : std::span<const Disc>{};
  const auto pair_bodies = disc_phases ? discs_->touching_bodies() : std::span<const DiscPair>{};
  const auto impacts = disc_phases ? discs_->impacts() : std::span<const DiscImpact>{};
  // Contacts and impacts that reached a sleeper: it acted as a static disc this tick. (The
  // touching disc pairs by their bodies: a plane or a segment never wakes a sleeper.)
  for (const DiscPair& p : pair_bodies) {
    const std::uint32_t a = p.a, b = p.b;
    if (asleep_[a] != 0 && asleep_[b] == 0 && types_[b] == BodyType::dynamic) {
      wake_bodies_.push_back(a), ++sleeper_contacts_;
    }
    if (asleep_[b] != 0 && asleep_[a] == 0 && types_[a] == BodyType::dynamic) {
      wake_bodies_.push_back(b), ++sleeper_contacts_;
    }
  }
  for (const DiscImpact& i : impacts) {
    for (const std::uint32_t j : {i.body_a, i.body_b}) {
      if (asleep_[j] != 0) wake_bodies_.push_back(j), ++sleeper_contacts_;
    }
  }
  wake_labelled();
  // Still ticks: dynamic discs below the speed (and their rims, when they roll).
  const double s2 = settings_.contacts->sleep_speed * settings_.contacts->sleep_speed;
  bool ready = false;
  for (const std::uint32_t k : disc_phases ? discs_->awake() : std::span<const std::uint32_t>{}) {
    const Disc& d = discs[k];
    const std::uint32_t j = d.body;
    if (asleep_[j] != 0 || types_[j] != BodyType::dynamic || d.sensor) continue;
    double v2 = double(vx_[j]) * double(vx_[j]) + double(vy_[j]) * double(vy_[j]);
    if (rolling_) v2 = std::max(v2, double(spin_[j]) * double(spin_[j]) * d.radius * d.radius);
    std::uint32_t& still = still_ticks_[j];
    still = v2 < s2 ? std::min(still_cap - 1, still) + 1 : 0;
    ready = ready || still >= sleep_ticks_;
  }
  if (shape_world_) ready = count_still_shapes(s2) || ready;  // world_shape_sleep.cpp
  for (const BodyInput& b : input.bodies) {
    if (bodies_.contains(b.body)) still_ticks_[bodies_.index(b.body)] = 0;
  }
  if (!ready) return;
  join_islands();
  std::vector<std::uint32_t>& falling = flip_scratch_;
  falling.clear();
  for_each_awake_body([&](std::uint32_t j) {
    if (types_[j] != BodyType::dynamic) return;
    const bool disc = !disc_of_.empty() && disc_of_[j] >= 0;
    if (!disc && !shape_sets_.set.contains(bodies_.dense[j])) return;  // a point body
    if (island_blocked_[detail::find_root(island_parent_, j)] != blocked_stamp_) {
      falling.push_back(j);
    }
  });
  for (const std::uint32_t j : falling) {
    // The root is the island's smallest index, so it is met first and takes the next number,
    // and the ring of its island (island_next_) starts at it.
    const std::uint32_t root = detail::find_root(island_parent_, j);
    fall_asleep(j, root == j ? take_island_number() : asleep_[root]);
    if (root == j) {
      island_next_[j] = j;
    } else {
      island_next_[j] = island_next_[root], island_next_[root] = j;
    }
  }
  immovable_dirty_ = true;
}

template <class Real>
void detail::WorldKernel<Real>::finish_sleep(const TickInput& input, bool discs) {
  if (discs || shape_world_) update_sleep(input, discs);
  contact_stats_.sleeping = sleepers_;
  contact_stats_.woken = woken_;
  contact_stats_.sleeper_contacts = sleeper_contacts_;
}

}  // namespace fixstep
