// Disc contacts, phase 2 begins: the resting contacts of the tick, gathered from the candidate
// pairs that touch at the tick's end (within the slop, and not an impact of the next tick) and
// from the discs on planes and segments, in key order: disc pairs, then planes and segments.
// With the tick's run of the second thread open (world_step.cpp, disc_events.cpp), the pairs
// are gathered in two passes over two halves of them, and the discs' plane contacts by halves,
// with the same contacts in the same order. In a large world (gather_warm.hpp) each disc pair
// also takes its warm start and its part of the split pile here (disc_halves.cpp), while its
// contact is in the cache.
#include <algorithm>
#include <atomic>
#include <cassert>
#include <cmath>
#include <limits>
#include <span>

#include "disc_contacts.hpp"
#include "fixstep/core/simd.hpp"
#include "simd_targets.hpp"

namespace fixstep::detail {

namespace {
std::atomic<std::size_t> gather_warm_from{min_gather_warm_pairs};

/// near[i] = 1 where disc i (centre x, y and radius r, m) touches one of the planes by
/// on(plane, x, y, r), else near[i] as it was, for a block of N discs: loops of a constant trip
/// count, which the compiler puts on SIMD lanes.
template <std::size_t N, class On>
[[gnu::always_inline]] inline void mark_near(std::span<const PlaneDef> planes, const double* x,
                                             const double* y, const double* r, double* near,
                                             On on) {
  for (const PlaneDef& p : planes) {
    for (std::size_t i = 0; i < N; ++i) near[i] = on(p, x[i], y[i], r[i]) ? 1.0 : near[i];
  }
}

// The same block for each SimdLevel (fixstep/core/simd.hpp), everything it calls inlined, as
// world_plane_blocks.cpp's tests: comparisons of sums and products each rounded alone (no
// contraction), so every level marks the same discs.
template <std::size_t N, class On>
[[gnu::noinline]] void mark_near_baseline(std::span<const PlaneDef> planes, const double* x,
                                          const double* y, const double* r, double* near, On on) {
  mark_near<N>(planes, x, y, r, near, on);
}
#if FIXSTEP_HAS_SIMD_CLONES
template <std::size_t N, class On>
[[gnu::flatten]] FIXSTEP_TARGET_AVX2 void mark_near_avx2(std::span<const PlaneDef> planes,
                                                         const double* x, const double* y,
                                                         const double* r, double* near, On on) {
  mark_near<N>(planes, x, y, r, near, on);
}
template <std::size_t N, class On>
[[gnu::flatten]] FIXSTEP_TARGET_AVX512 void mark_near_avx512(std::span<const PlaneDef> planes,
                                                             const double* x, const double* y,
                                                             const double* r, double* near, On on) {
  mark_near<N>(planes, x, y, r, near, on);
}
#endif

template <std::size_t N, class On>
void mark_near_at(SimdLevel level, std::span<const PlaneDef> planes, const double* x,
                  const double* y, const double* r, double* near, On on) {
#if FIXSTEP_HAS_SIMD_CLONES
  if (level == SimdLevel::avx512) return mark_near_avx512<N>(planes, x, y, r, near, on);
  if (level == SimdLevel::avx2) return mark_near_avx2<N>(planes, x, y, r, near, on);
#endif
  (void)level;
  mark_near_baseline<N>(planes, x, y, r, near, on);
}

}  // namespace

void set_gather_warm_pairs(std::size_t pairs) {
  gather_warm_from.store(pairs, std::memory_order_relaxed);
}

std::size_t gather_warm_pairs() {
  return gather_warm_from.load(std::memory_order_relaxed);
}

// Inlined into its callers, so that a contact is made in registers and stored once where it
// goes (a call wrote it to the stack field by field, and the copy after read it back in wider
// loads than the stores: each load waited for the stores to retire).
template <class Real>
[[gnu::always_inline]] inline bool DiscContacts<Real>::pair_contact(
    const Tick& tick, const DiscPair& p, RestContact* out, const WarmImpulse*& warm_at) const {
  const Disc &da = discs_[p.a], &db = discs_[p.b];
  const double dx = ex_[p.a] - ex_[p.b], dy = ey_[p.a] - ey_[p.b];
  const double dist = length(dx, dy);
  const double gap = dist - (da.radius + db.radius);
  if (gap > slop * std::min(da.radius, db.radius)) return false;
  // Two discs at one point (dist 0) take n = (0, 1). The divisor is never 0: a compiler may
  // divide before it selects, and Debug tests trap a division by zero (a divisor below the
  // least normal double, never a contact's, is that least one).
  const double safe = std::max(dist, std::numeric_limits<double>::min());
  const double nx = dist > 0.0 ? dx / safe : 0.0, ny = dist > 0.0 ? dy / safe : 1.0;
  // A pair still apart that closes faster than one tick of relative acceleration is an
  // impact of the next tick, not a resting contact. The acceleration counts the pair's own
  // contact force of the last tick: its resting impulse λ_n, which changed the pair's relative
  // velocity by λ_n (1/m_a + 1/m_b). Discs that fall together have no relative acceleration of
  // their own, so without it a contact that carried a pile's load and closes by the tiny speeds
  // its neighbours' shifts give it would be dropped, its load with it, and caught again as an
  // impact: the pile's contacts would churn every tick.
  const double vn = (evx_[p.a] - evx_[p.b]) * nx + (evy_[p.a] - evy_[p.b]) * ny;
  const double cn =
      (motion_[p.a].ax - motion_[p.b].ax) * nx + (motion_[p.a].ay - motion_[p.b].ay) * ny;
  // (The last impulse is looked up only for a pair that closes faster than the free part.)
  if (gap > 0.0 && -vn > std::abs(cn) * tick.dt &&
      -vn > std::abs(cn) * tick.dt + last_impulse(p, warm_at) * (da.inv_mass + db.inv_mass)) {
    return false;
  }
  if (out == nullptr) return true;
  // Every field written once, in one initializer: assigning the fields over a zeroed contact
  // (RestContact{}) cleared it with a string instruction first, per contact.
  RestContact& c = *out;
  c = RestContact{.a = p.a,
                  .b = p.b,
                  .nx = nx,
                  .ny = ny,
                  .friction = std::sqrt(da.friction * db.friction),
                  .inv_a = da.inv_mass,
                  .inv_b = db.inv_mass,
                  .radii = da.radius + db.radius,
                  .r_min = std::min(da.radius, db.radius)};
  // In a large world the warm start is matched here, while the contact is in the cache (a
  // pass over the contacts after the gather read each one again from memory).
  if (warm_gathered_) {
    if (const WarmImpulse* const w = warm(p, warm_at)) {
      c.lambda_n = w->lambda_n, c.lambda_t = w->lambda_t;
    }
  }
  return true;
}

template <class Real>
const WarmImpulse* DiscContacts<Real>::warm(const DiscPair& p, const WarmImpulse*& at) const {
  const std::uint64_t key = pair_key(p);
  const WarmImpulse *const begin = warm_.data(), *const end = begin + warm_pairs_;
  if (at != begin && (at - 1)->key >= key) at = first_warm_from(begin, at, key);  // went back
  while (at != end && at->key < key) ++at;  // pairs come in key order: a walk
  return at != end && at->key == key && at->lambda_n > 0.0 ? at : nullptr;
}

template <class Real>
const WarmImpulse* DiscContacts<Real>::warm_from(std::size_t i) const {
  if (i >= pairs_.size()) return warm_.data();
  return first_warm_from(warm_.data(), warm_.data() + warm_pairs_, pair_key(pairs_[i]));
}

template <class Real>
void DiscContacts<Real>::gather_contacts(const Tick& tick) {
  const std::size_t m = pairs_.size();
  warm_gathered_ = m >= gather_warm_pairs();
  on_moving_segment_.clear();
  cut_before_gather();
  const bool cut = cut_state_ == cut_made;  // each pair's part found here (split_contacts())
  bool kinematic[2] = {false, false};
  if (sharing() && m >= min_parallel_gather) {
    // Two threads: which pairs touch, by halves of the pairs; then each half's contacts,
    // the second half's after the first's (the same contacts in the same order as one pass).
    std::size_t found[2] = {0, 0};
    touch_.resize(m);
    halves(m, [&](std::size_t begin, std::size_t end, int half) {
      std::size_t count = 0;
      const WarmImpulse* warm_at = warm_from(begin);
      for (std::size_t i = begin; i < end; ++i) {
        touch_[i] = pair_contact(tick, pairs_[i], nullptr, warm_at) ? 1 : 0;
        count += touch_[i];
      }
      found[half] = count;
    });
    contacts_.resize(found[0] + found[1]);
    touching_bodies_.resize(contacts_.size());
    part_.resize(cut ? contacts_.size() : 0);
    halves(m, [&](std::size_t begin, std::size_t end, int half) {
      std::size_t at = half == 1 ? found[0] : 0;
      bool moving = false;
      const WarmImpulse* warm_at = warm_from(begin);
      for (std::size_t i = begin; i < end; ++i) {
        if (!touch_[i]) continue;
        const DiscPair& p = pairs_[i];
        touching_bodies_[at] = {discs_[p.a].body, discs_[p.b].body};
        if (cut) part_[at] = part_of(side_[p.a], side_[p.b]);
        RestContact& c = contacts_[at++];
        [[maybe_unused]] const bool touches = pair_contact(tick, p, &c, warm_at);
        assert(touches);  // the same arithmetic as the first pass (no contraction)
        moving = moving || moving_kinematic(p.a) || moving_kinematic(p.b);
      }
      kinematic[half] = moving;
    });
    touch_.clear();  // scratch: a snapshot need not copy it
  } else {
    // The pairs' bodies and parts written in place, at most one a pair (a push_back of a part
    // was a call per contact), then cut to the count.
    contacts_.clear();
    touching_bodies_.resize(m);
    part_.resize(cut ? m : 0);
    std::size_t count = 0;
    RestContact c;
    const WarmImpulse* warm_at = warm_from(0);
    for (const DiscPair& p : pairs_) {
      if (!pair_contact(tick, p, &c, warm_at)) continue;
      kinematic[0] = kinematic[0] || moving_kinematic(p.a) || moving_kinematic(p.b);
      contacts_.push_back(c);
      touching_bodies_[count] = {discs_[p.a].body, discs_[p.b].body};
      if (cut) part_[count] = part_of(side_[p.a], side_[p.b]);
      ++count;
    }
    touching_bodies_.resize(count);
    part_.resize(cut ? count : 0);
  }
  kinematic_contacts_ = kinematic[0] || kinematic[1];
  plane_contacts_ = static_cast<std::uint32_t>(contacts_.size());
  if (tick.planes.empty() && tick.segments == nullptr) return;  // nothing but disc pairs
  sort_live();                                                  // the walls' contacts in key order
  const std::size_t live = live_count();
  if (tick.segments == nullptr && sharing()) {
    // Two threads: each half of the discs' plane contacts apart, then the first's and the
    // second's after the pairs (the same contacts in the same order).
    for (auto& half : plane_half_) half.clear();
    halves(live, [&](std::size_t begin, std::size_t end, int half) {
      plane_contacts_in(tick, begin, end, plane_half_[half]);
    });
    for (auto& half : plane_half_) {
      contacts_.insert(contacts_.end(), half.begin(), half.end());
      half.clear();  // scratch: a snapshot need not copy it
    }
    return;
  }
  if (tick.segments == nullptr) {
    plane_contacts_in(tick, 0, live, contacts_);
    return;
  }
  live_range(0, live, [&](std::uint32_t k) {
    plane_contacts_of(tick, k, contacts_);
    if (discs_[k].dynamic && !discs_[k].sensor) gather_segment_contacts(tick, k);
  });
}

// The walls' contacts of live positions [begin, end), in disc then plane order. With every
// disc live, in blocks of wall_block discs, plane by plane (on_plane's test on SIMD lanes, for
// each SimdLevel): most discs touch no wall.
template <class Real>
void DiscContacts<Real>::plane_contacts_in(const Tick& tick, std::size_t begin, std::size_t end,
                                           std::vector<RestContact>& out) const {
  if (!live_all_) {
    live_range(begin, end, [&](std::uint32_t k) { plane_contacts_of(tick, k, out); });
    return;
  }
  const SimdLevel level = simd_level();
  const auto on = [](const PlaneDef& p, double x, double y, double r) {
    return on_plane(p, x, y, r);
  };
  alignas(64) double x[wall_block], y[wall_block], r[wall_block];
  alignas(64) double near[wall_block];  // 1 where a wall is within the slop (doubles: SIMD)
  for (std::size_t b = begin; b < end; b += wall_block) {
    const std::size_t m = std::min(wall_block, end - b);
    for (std::size_t i = 0; i < wall_block; ++i) {  // past m, the block's first disc again
      const std::size_t k = b + (i < m ? i : 0);
      x[i] = ex_[k], y[i] = ey_[k], r[i] = discs_[k].radius, near[i] = 0.0;
    }
    mark_near_at<wall_block>(level, tick.planes, x, y, r, near, on);
    for (std::size_t i = 0; i < m; ++i) {
      if (near[i] != 0.0) plane_contacts_of(tick, static_cast<std::uint32_t>(b + i), out);
    }
  }
}

template <class Real>
void DiscContacts<Real>::plane_contacts_of(const Tick& tick, std::uint32_t k,
                                           std::vector<RestContact>& out) const {
  const auto n = static_cast<std::uint32_t>(discs_.size());
  const Disc& d = discs_[k];
  if (!d.dynamic || d.sensor) return;
  for (std::uint32_t i = 0; i < tick.planes.size(); ++i) {
    const PlaneDef& p = tick.planes[i];
    if (!on_plane(p, ex_[k], ey_[k], d.radius)) continue;
    out.push_back(wall_contact(k, n + i, p.normal.x, p.normal.y, p.friction));
  }
}

template <class Real>
RestContact DiscContacts<Real>::wall_contact(std::uint32_t k, std::uint32_t b, double nx, double ny,
                                             double friction) const {
  const Disc& d = discs_[k];
  RestContact c;
  c.a = k, c.b = b;
  c.radii = c.r_min = d.radius;
  c.nx = nx, c.ny = ny;
  c.inv_a = d.inv_mass;
  c.friction = friction;
  return c;
}

}  // namespace fixstep::detail
