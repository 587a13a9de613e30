// Disc contacts, phase 1: the discs' motions in the tick, a pair's next impact
// and its resolution (see disc_contacts.hpp for the model; the queue: disc_queue.cpp).
#include <algorithm>
#include <cmath>
#include <limits>

#include "copy_bytes.hpp"
#include "disc_contacts.hpp"
#include "disc_toi.hpp"
#include "fixstep/core/components.hpp"
#include "fixstep/core/limits.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/stop_request.hpp"
#include "fixstep/core/world_settings.hpp"
#include "phase_clock.hpp"

namespace fixstep::detail {

namespace {

constexpr double eps = std::numeric_limits<double>::epsilon();

/// Whether a pair whose centres are sqrt(d2) apart (d2 in m², the rounded sum of squares that
/// length() takes the root of) both touches as next_event() tests it and closes more slowly
/// than the resting speed `resting` / dt, told without the square root, the normal and its
/// division: where true, next_event() finds no event, so a pile's resting pairs, at relative
/// speeds near 0, skip them. R = r_a + r_b (m); `resting`: the slop of the smaller radius (m);
/// dt in s.
/// - Touches: d2 <= R² (1 - 2⁻²⁰) rounded gives sqrt(d2) <= R, so dist - R <= 0.
/// - Slower: |w·n| <= |w_x| + |w_y| for a unit n, here below the resting speed by 2⁻²⁰ of it
///   less rounding. next_event's rounded -w·n exceeds the bound by a few ε of it at most (n =
///   d/|d| rounded; |d| >= 2⁻⁴⁸⁰, far from underflow), within its own tolerance.
bool resting_without_root(const RelativeMotion& r, double d2, double resting, double dt) {
  constexpr double far_from_underflow = 0x1p-960;  // |d| >= 2⁻⁴⁸⁰
  constexpr double below = 1.0 - 0x1p-20;
  return d2 >= far_from_underflow && d2 <= r.radius * r.radius * below &&
         (std::abs(r.wx) + std::abs(r.wy)) * dt <= resting * below;
}

}  // namespace

template <class Real>
void DiscContacts<Real>::rebuild(std::vector<Disc> discs, std::vector<std::uint64_t> linked,
                                 std::vector<CollisionFilter> filters,
                                 const ContactSettings& settings) {
  discs_ = std::move(discs);
  linked_ = std::move(linked);
  filters_ = std::move(filters);
  sensor_pairs_.clear(), sensed_.clear();
  // The last tick's contacts name discs of the old set (touching() until the next gather).
  contacts_.clear(), touching_bodies_.clear(), plane_contacts_ = 0;
  settings_ = settings;
  const std::size_t n = discs_.size();
  min_radius_ = std::numeric_limits<double>::infinity();
  max_radius_ = 0;
  for (const Disc& d : discs_) {
    min_radius_ = std::min(min_radius_, d.radius);
    if (std::isfinite(d.radius)) max_radius_ = std::max(max_radius_, d.radius);
  }
  if (!(max_radius_ > 0.0)) max_radius_ = 1.0;
  for (auto* v : {&x0_, &y0_, &vx0_, &vy0_}) v->assign(n, Real(0));
  for (auto* v : {&ex_, &ey_, &evx_, &evy_, &lost_, &external_, &d_begin_}) {
    v->assign(n, 0.0);
  }
  motion_.assign(n, DiscMotion{});
  model_offset_.assign(n, DiscOffset{});
  boxes_.assign(n, SweptBox{});
  dynamic_.resize(n);
  for (std::size_t k = 0; k < n; ++k) dynamic_[k] = discs_[k].dynamic;
  offset_.assign(n + 1, 0);
  stamp_.assign(n, 0);
  held_.assign(n, HeldMotion{});
  for (ImpactLane& q : lanes_) q.held.clear(), q.extra.clear(), q.grown.clear(), q.mark = 0;
  lane_misses_in_a_row_ = lane_rest_ = 0, lane_ticks_ = lanes_undone_ = lane_cuts_ = pile_cuts_ = 0;
  extra_head_.assign(n, ExtraPair::none);
  grown_of_.assign(n, GrownBox::none);
  partner_mark_.assign(n, 0);
  impacts_.assign(n, 0);
  changed_.assign(n, 0);
  walled_.assign(n, 0);
  warm_.clear(), warm_pairs_ = 0;
  rolling_ = settings.rolling;
  ew_.assign(rolling_ ? n : 0, 0.0), ew0_.assign(rolling_ ? n : 0, 0.0);
  asleep_.assign(n, 0), sleeper_count_ = 0, awake_dirty_ = true;
  awake_flips_.whole = true, awake_flips_.discs.clear();
  live_all_ = true, live_.clear(), in_live_.assign(n, 0), live_sorted_ = true;
  waking_ = false, woken_.clear(), sleepers_.grid.stale = true, saved_live_ = false;
  fat_ = FatBoxes{}, fat_grid_.value = false;
  degree_.resize(n), cursor_.resize(n);
}

template <class Real>
void DiscContacts<Real>::set_accelerations(std::span<const Real> ax, std::span<const Real> ay) {
  for (Disc& d : discs_) d.accel_x = double(ax[d.body]), d.accel_y = double(ay[d.body]);
}

template <class Real>
void DiscContacts<Real>::save_start(const Real* x, const Real* y, const Real* vx, const Real* vy,
                                    const Real* dissipated) {
  // A tick that visits the live discs only saves the awake ones (the rest join from rest).
  auto save = [&](std::uint32_t k) {
    const std::uint32_t j = discs_[k].body;
    x0_[k] = x[j], y0_[k] = y[j], vx0_[k] = vx[j], vy0_[k] = vy[j];
    d_begin_[k] = dissipated ? double(dissipated[j]) : 0.0;
  };
  // By halves within the tick's run of the second thread (each disc's copy its own), from
  // min_parallel_copies discs.
  saved_live_ = sleeper_count_ != 0 && (awake(), live_only());
  if (saved_live_) {
    halves_from(awake_list_.size(), min_parallel_copies,
                [&](std::size_t begin, std::size_t end, int /*half*/) {
                  for (std::size_t i = begin; i < end; ++i) save(awake_list_[i]);
                });
  } else {
    halves_from(discs_.size(), min_parallel_copies,
                [&](std::size_t begin, std::size_t end, int /*half*/) {
                  for (std::size_t k = begin; k < end; ++k) save(static_cast<std::uint32_t>(k));
                });
  }
}

template <class Real>
void DiscContacts<Real>::save_spin_start(const Real* spin) {
  if (saved_live_) {
    for (const std::uint32_t k : awake_list_) ew0_[k] = double(spin[discs_[k].body]);
  } else {
    for (std::size_t k = 0; k < ew0_.size(); ++k) ew0_[k] = double(spin[discs_[k].body]);
  }
}

template <class Real>
void DiscContacts<Real>::build_motions(const Tick& tick) {
  bounced_[0].clear(), bounced_[1].clear();
  if (live_all_) {
    halves(discs_.size(), [&](std::size_t begin, std::size_t end, int half) {
      build_motions(tick, begin, end, bounced_[half]);
    });
    return;
  }
  halves(live_.size(), [&](std::size_t begin, std::size_t end, int half) {
    live_range(begin, end, [&](std::uint32_t k) { build_motions(tick, k, k + 1, bounced_[half]); });
  });
}

template <class Real>
void DiscContacts<Real>::build_motions(const Tick& tick, std::size_t begin, std::size_t end,
                                       ScratchVector<std::uint32_t>& bounced) {
  const double dt = tick.dt;
  for (std::size_t k = begin; k < end; ++k) {
    const Disc& d = discs_[k];
    const std::uint32_t j = d.body;
    const double x1 = tick.x[j], y1 = tick.y[j], v1x = tick.vx[j], v1y = tick.vy[j];
    const double x0 = x0_[k], y0 = y0_[k], v0x = vx0_[k], v0y = vy0_[k];
    ex_[k] = x1, ey_[k] = y1, evx_[k] = v1x, evy_[k] = v1y;
    DiscMotion& m = motion_[k];
    DiscOffset& o = model_offset_[k];
    o.x = (x1 - x0) / dt - 0.5 * (v0x + v1x), o.y = (y1 - y0) / dt - 0.5 * (v0y + v1y);
    m.t = 0, m.x = x0, m.y = y0, m.ux = v0x + o.x, m.uy = v0y + o.y, m.radius = d.radius;
    m.ax = (v1x - v0x) / dt, m.ay = (v1y - v0y) / dt;
    const double pad = box_pad(d);
    SweptBox& b = boxes_[k];
    if (d.plane_slot >= 0 && tick.after_t[d.plane_slot] >= 0.0) {
      // It bounced in the plane pass: on its free motion until its first plane event, and on
      // its motion after the last one from then on (switch(); a disc impact before then
      // changes its free motion instead, and it meets the walls in the disc pass).
      const PlaneMotion& p = tick.after[d.plane_slot];
      o.x = p.free_dx, o.y = p.free_dy, m.ux = v0x + o.x, m.uy = v0y + o.y;
      m.ax = p.free_ax, m.ay = p.free_ay;
      // Its spin too: the plane pass's friction turned it with the same impulse that changed
      // its velocity, so the two go together (a disc pass taking the turn without the velocity
      // change would make energy).
      if (rolling_) ew_[k] = p.free_w;
      plane_box(p, tick.after_t[d.plane_slot], m, pad, dt, b);
      bounced.push_back(static_cast<std::uint32_t>(k));
    } else {
      // The box of the motion over the whole tick.
      motion_extent(x0, m.ux, m.ax, dt, pad, b.min_x, b.max_x);
      motion_extent(y0, m.uy, m.ay, dt, pad, b.min_y, b.max_y);
    }
    stamp_[k] = 0, impacts_[k] = 0, changed_[k] = 0, walled_[k] = 0;
    lost_[k] = 0, external_[k] = 0;
  }
}

template <class Real>
void DiscContacts<Real>::plane_box(const PlaneMotion& p, double t, const DiscMotion& free,
                                   double pad, double dt, SweptBox& b) {
  // The free motion up to the first plane event, and the motion after the last one from the
  // first on (extrapolated back over the plane events between).
  motion_extent(free.x, free.ux, free.ax, p.first, pad, b.min_x, b.max_x);
  motion_extent(free.y, free.uy, free.ay, p.first, pad, b.min_y, b.max_y);
  add_plane_motion(p, t, p.first, dt, pad, b);
}

template <class Real>
void DiscContacts<Real>::switch_to_plane_motion(const Tick& tick, std::uint32_t k) {
  const PlaneMotion& p = tick.after[discs_[k].plane_slot];
  DiscMotion& m = motion_[k];
  m.t = tick.after_t[discs_[k].plane_slot], m.x = p.x, m.y = p.y, m.ux = p.ux, m.uy = p.uy,
  m.ax = p.ax, m.ay = p.ay;
  model_offset_[k] = DiscOffset{p.dx, p.dy};
  if (rolling_) ew_[k] = double(tick.spin[discs_[k].body]);  // the spin after its last event
  ++stamp_[k];
}

template <class Real>
void DiscContacts<Real>::predict(ImpactLane& q, std::uint32_t pair, double now, double dt) {
  DiscEvent ev;
  if (!next_event(pair, now, dt, ev)) return;
  q.heap.push_back(ev);
  std::push_heap(q.heap.begin(), q.heap.end(), later_event);
}

template <class Real>
bool DiscContacts<Real>::next_event(std::uint32_t pair, double now, double dt,
                                    DiscEvent& out) const {
  const std::uint32_t a = pairs_[pair].a, b = pairs_[pair].b;
  const DiscMotion &ma = motion_[a], &mb = motion_[b];
  RelativeMotion r;
  r.px = ma.px(now) - mb.px(now), r.py = ma.py(now) - mb.py(now);
  r.wx = ma.ux + ma.ax * (now - ma.t) - mb.ux - mb.ax * (now - mb.t);
  r.wy = ma.uy + ma.ay * (now - ma.t) - mb.uy - mb.ay * (now - mb.t);
  r.cx = ma.ax - mb.ax, r.cy = ma.ay - mb.ay;
  r.radius = ma.radius + mb.radius;
  const double r_min = std::min(ma.radius, mb.radius);
  const double d2 = r.px * r.px + r.py * r.py;
  if (resting_without_root(r, d2, slop * r_min, dt)) return false;
  const double dist = length(r.px, r.py);  // the root of d2 (the same sum, computed once)
  const double scale = std::abs(ma.px(now)) + std::abs(ma.py(now)) + r.radius + dist;
  // Approaching faster than one tick of relative acceleration: an impact (else resting).
  auto impact_speed = [&](double s, double rest) {
    const double dx = r.px + s * (r.wx + 0.5 * s * r.cx), dy = r.py + s * (r.wy + 0.5 * s * r.cy);
    const double len = length(dx, dy);
    if (!(len > 0.0)) return false;
    const double nx = dx / len, ny = dy / len;
    const double vn = (r.wx + s * r.cx) * nx + (r.wy + s * r.cy) * ny;
    const double cn = r.cx * nx + r.cy * ny;
    const double vtol = 64.0 * eps * (scale / dt + length(r.wx, r.wy));
    return -vn > std::abs(cn) * dt + rest + vtol;
  };
  double when = std::numeric_limits<double>::infinity();
  if (dist - r.radius <= 16.0 * eps * scale) {
    // Already in contact: closing slower than the slop in a tick is resting (phase 2).
    const double rest = slop * r_min / dt;
    if (impact_speed(0.0, rest)) when = now;
  } else {
    const double h = horizon_ - now;
    const double s = first_contact(r, h);
    if (s <= h && impact_speed(s, 0.0)) {
      when = now + s;
    } else if (!(s <= h)) {
      // Rounding may leave a pair that meets at the very end of the tick a hair apart: an
      // impact at the end of the tick.
      const double ex = r.px + h * (r.wx + 0.5 * h * r.cx), ey = r.py + h * (r.wy + 0.5 * h * r.cy);
      if (length(ex, ey) - r.radius <= 16.0 * eps * scale && impact_speed(h, 0.0)) when = horizon_;
    }
  }
  if (when > horizon_) return false;
  out = DiscEvent{when, pair, stamp_[a], stamp_[b]};
  return true;
}

template <class Real>
void DiscContacts<Real>::impact(ImpactLane& q, std::uint32_t pair, double now, double dt) {
  const std::uint32_t a = pairs_[pair].a, b = pairs_[pair].b;
  DiscMotion &ma = motion_[a], &mb = motion_[b];
  if (held_[a].on && !discs_[b].dynamic) release(a);  // a kinematic disc pushes a held one on
  if (held_[b].on && !discs_[a].dynamic) release(b);
  ma.advance(now), mb.advance(now);
  const double len = length(ma.x - mb.x, ma.y - mb.y);
  const double nx = len > 0.0 ? (ma.x - mb.x) / len : 0.0,
               ny = len > 0.0 ? (ma.y - mb.y) / len : 1.0;
  const double wx = ma.ux - mb.ux, wy = ma.uy - mb.uy;
  const double vn = std::min(wx * nx + wy * ny, 0.0);
  const double cn = (ma.ax - mb.ax) * nx + (ma.ay - mb.ay) * ny;
  const Disc &da = discs_[a], &db = discs_[b];
  double e = std::max(da.restitution, db.restitution);
  if (e * -vn <= std::max(-cn, 0.0) * dt) e = 0.0;  // it would hit again within the tick: rest
  // A held disc stays where it is for the rest of the tick: immovable (infinite mass, at rest).
  const double ia = held_[a].on ? 0.0 : da.inv_mass, ib = held_[b].on ? 0.0 : db.inv_mass;
  const double ja = held_[a].on ? 0.0 : da.inv_inertia, jb = held_[b].on ? 0.0 : db.inv_inertia;
  const double mass = 1.0 / (ia + ib);
  const double jn = -(1.0 + e) * vn * mass;
  q.log.push_back(DiscImpact{da.body, db.body, now, -vn});
  // Coulomb over the normal impulse: the tangential relative velocity loses at most μ jn/m.
  const double tx = wx - (wx * nx + wy * ny) * nx, ty = wy - (wx * nx + wy * ny) * ny;
  const double speed = length(tx, ty);
  const double mu = std::sqrt(da.friction * db.friction);
  const double jt = std::min(speed * mass, mu * jn);
  double jx = jn * nx - (speed > 0.0 ? jt * tx / speed : 0.0);
  double jy = jn * ny - (speed > 0.0 ? jt * ty / speed : 0.0);
  if (rolling_) {  // friction at the contact point: the discs' turn slips there too
    // The contact point divides the line of centres in the ratio of the radii (at the
    // computed time of impact |x_a - x_b| = r_a + r_b to rounding): the arms add up to the
    // distance, so the impulse changes no angular momentum about any point.
    const double scale = len > 0.0 ? len / (da.radius + db.radius) : 1.0;
    const double ra = da.radius * scale, rb = db.radius * scale;
    const double slip = -wx * ny + wy * nx - (ew_[a] * ra + ew_[b] * rb);
    const double mass_t = 1.0 / (ia + ib + ra * ra * ja + rb * rb * jb);
    const double lt = std::clamp(-slip * mass_t, -mu * jn, mu * jn);
    jx = jn * nx - lt * ny, jy = jn * ny + lt * nx;
    ew_[a] -= ra * ja * lt, ew_[b] -= rb * jb * lt;
  }
  // The work of a kinematic disc's impulse is external (J·V over the impulse).
  if (!da.dynamic) external_[b] -= jx * ma.ux + jy * ma.uy;
  if (!db.dynamic) external_[a] += jx * mb.ux + jy * mb.uy;
  ma.ux += ia * jx, ma.uy += ia * jy;
  mb.ux -= ib * jx, mb.uy -= ib * jy;
  for (const std::uint32_t k : {a, b}) {
    if (!discs_[k].dynamic || held_[k].on) continue;
    ++stamp_[k], ++impacts_[k], changed_[k] = 1;
  }
}

template <class Real>
void DiscContacts<Real>::resolve(const Tick& tick, ContactStats& stats, StepProfile& profile) {
  stats = ContactStats{};
  lanes_[0].log.clear();
  sensor_pairs_.clear(), sensed_.clear();
  cap_ = CapHit{};
  PhaseClock clock(true);
  // Two threads: the worker spins through the tick's passes (see SecondThread), if the
  // world has not opened its run already.
  const SecondThreadRun run(second_thread(tick.threads));
  begin_live();
  if (rolling_) {
    live_range(0, live_count(),
               [&](std::uint32_t k) { ew_[k] = double(tick.spin[discs_[k].body]); });
  }
  build_motions(tick);
  waking_ = !live_all_;
  if (tick.wake) tick.wake(tick.wake_context);
  waking_ = false;
  if (!live_all_) add_woken_and_near(tick);
  stats.disc_visited = live_count();
  const int windows = tick_windows(tick, stats);
  stats.windows = static_cast<std::size_t>(windows);
  profile.broadphase = clock.lap();
  profile.impacts = profile.resting = 0.0;
  if (windows == 0) return;
  run_events(tick, stats, windows);
  profile.impacts = clock.lap();
  gather_contacts(tick);
  split_contacts(stats);
  solve_resting(tick, stats);  // and the impulses kept for the next tick (scatter_rows)
  profile.resting = clock.lap();
  finish(tick);
  if (!sensor_pairs_.empty()) detect_sensors(tick);
  stats.disc_visited = live_count();  // with the sleepers the impacts reached
}

template <class Real>
std::size_t DiscContacts<Real>::bytes() const {
  return copy_bytes(discs_, linked_, filters_, sensor_pairs_, sensed_, x0_, y0_, vx0_, vy0_,
                    motion_, model_offset_, boxes_, dynamic_, pairs_, offset_, incident_, cursor_,
                    stamp_, held_, extra_sorted_, partner_mark_, wall_found_, extra_head_,
                    grown_of_, impacts_, changed_, walled_, touch_, plane_half_[0], plane_half_[1],
                    events_, contacts_, touching_bodies_, on_moving_segment_, order_, cut_, side_,
                    part_, lane_of_, lane_parent_, lane_log_, warm_, ex_, ey_, evx_, evy_, lost_,
                    external_, d_begin_, ew_, ew0_, rows_, push_rows_, row_moved_, sv_, slot_moved_,
                    roll_rows_, sw_, asleep_, awake_list_, awake_flips_.discs, awake_flips_.scratch,
                    live_, in_live_, woken_, sleepers_.grid.discs, sleepers_.disc,
                    sleepers_.indexed, sleepers_.extra, sleepers_.extras, live_boxes_,
                    live_dynamic_, degree_, degree_half_, cursor_half_, fat_half_, fat_.boxes,
                    fat_.pairs, segments_near_, bounced_[0], bounced_[1]) +
         lanes_[0].bytes() + lanes_[1].bytes();
}

}  // namespace fixstep::detail
