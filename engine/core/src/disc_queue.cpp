// Disc contacts, phase 1: the event queue of a tick's impacts. Each pair's first impact, and each
// bounced disc's switch to the plane pass's motion, go into one queue in time order (ties by
// pair order, a disc's wall events after every pair's); impacts are resolved as they come, and
// the pairs, the path beyond the box and the walls of a disc whose motion changed are predicted
// again (see disc_contacts.hpp for the model). The queue runs over the tick's windows in turn
// (disc_windows.cpp), each up to its end.
#include <algorithm>

#include "disc_contacts.hpp"
#include "fixstep/core/limits.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/stop_request.hpp"

namespace fixstep::detail {

template <class Real>
void DiscContacts<Real>::first_events(const Tick& tick, double from) {
  // Each pair's first event from `from`: independent of the others, so two threads share the
  // pairs; the heap pops them in (time, pair) order whatever order they are found in. Events
  // left from an earlier window (walls, switches) stay.
  const auto m = static_cast<std::uint32_t>(pairs_.size());
  auto find = [&](std::uint32_t begin, std::uint32_t end, std::vector<DiscEvent>& out) {
    DiscEvent ev;
    for (std::uint32_t i = begin; i < end; ++i) {
      if (next_event(i, from, tick.dt, ev)) out.push_back(ev);
    }
  };
  ScratchVector<DiscEvent>& heap = lanes_[0].heap;
  if (sharing() && m >= min_parallel_pairs) {
    events_.clear();
    auto halves = [&](int half) { half == 0 ? find(0, m / 2, heap) : find(m / 2, m, events_); };
    broadphase_.second_thread().both(halves);
    heap.insert(heap.end(), events_.begin(), events_.end());
  } else {
    find(0, m, heap);
  }
  if (from == 0.0 && (!tick.planes.empty() || tick.segments)) {  // bounced by the plane pass
    each_bounced([&](std::uint32_t k) { heap.push_back(switch_of(tick, k)); });
  }
  std::make_heap(heap.begin(), heap.end(), later_event);
}

template <class Real>
void DiscContacts<Real>::predict_pairs(ImpactLane& q, std::uint32_t k, double now, double dt,
                                       std::uint64_t& again) {
  again += degree_[k];
  const std::uint32_t end = offset_[k] + degree_[k];
  for (std::uint32_t i = offset_[k]; i < end; ++i) predict(q, incident_[i], now, dt);
  for (std::uint32_t e = extra_head_[k]; e != ExtraPair::none; e = q.extra[e].next) {
    ++again, predict(q, q.extra[e].pair, now, dt);
  }
}

template <class Real>
void DiscContacts<Real>::predict_after(ImpactLane& q, const Tick& tick, std::uint32_t k, double now,
                                       std::uint64_t& again) {
  const double dt = tick.dt;
  predict_pairs(q, k, now, dt, again);
  again += reach(q, tick, k, now, dt) / 16;  // the pairs of its path beyond its box
  if (!tick.planes.empty() || tick.segments) predict_wall(q, tick, k, now, dt, again);
}

template <class Real>
bool DiscContacts<Real>::run_window(ImpactLane& q, const Tick& tick, ContactStats& stats) {
  const double dt = tick.dt;
  EventBudget& budget = q.budget;
  std::uint64_t& again = budget.again;
  ScratchVector<DiscEvent>& heap = q.heap;
  while (!heap.empty() && !(heap.front().time > horizon_)) {
    if (q.split && lanes_met()) return false;  // the tick's impacts run again in one lane
    std::pop_heap(heap.begin(), heap.end(), later_event);
    const DiscEvent ev = heap.back();
    heap.pop_back();
    if (ev.pair & switch_event) {  // a disc met its first plane event on its free motion
      const std::uint32_t k = ev.pair & ~switch_event;
      if (ev.stamp_a != stamp_[k]) continue;  // an impact came first
      if (tick.after_t[discs_[k].plane_slot] > ev.time) {
        // Its plane events did not all fall at this time (a corner): the plane pass's motion
        // after the last one, extrapolated back to this first one, lies beyond a wall until
        // then, where a disc could meet it. Its walls are met here instead, from its free
        // motion on, as after an impact.
        predict_wall(q, tick, k, ev.time, dt, again);
        continue;
      }
      switch_to_plane_motion(tick, k);
      walled_[k] = 1;
      predict_pairs(q, k, motion_[k].t, dt, again);  // within its box, clear of the walls
      continue;
    }
    if (ev.pair & wall_event) {  // a disc's impact with a wall (disc_walls.cpp)
      const std::uint32_t k = ev.pair & ~wall_event;
      if (ev.stamp_a != stamp_[k]) continue;  // superseded
      if (again > budget.cap) return over_budget(q, stats, k, CapHit::npos, ev.time);
      const WallOutcome out = wall_impact(q, tick, k, ev.stamp_b, ev.time);
      if (out == WallOutcome::none) continue;
      ++(out == WallOutcome::held ? stats.held : stats.wall_impacts);
      predict_after(q, tick, k, ev.time, again);
      continue;
    }
    const std::uint32_t a = pairs_[ev.pair].a, b = pairs_[ev.pair].b;
    if (ev.stamp_a != stamp_[a] || ev.stamp_b != stamp_[b]) continue;  // superseded
    // What predict_after() reads of the two discs once the impact is resolved: asked for now,
    // it arrives while the impact is computed (in a large gas each is a cache miss).
    for (const std::uint32_t k : {a, b}) {
      __builtin_prefetch(&boxes_[k]);
      __builtin_prefetch(&grown_of_[k]);
      __builtin_prefetch(&extra_head_[k]);
      __builtin_prefetch(&offset_[k]);
    }
    const PastCap past = past_cap(tick, ev.pair, ev.time);
    if (past == PastCap::rest) continue;  // the resting solver's (see disc_contacts.hpp)
    // An impact due that the cap leaves unresolved.
    if (again > budget.cap) return over_budget(q, stats, a, b, ev.time);
    if (past == PastCap::hold) {
      const std::size_t held = hold_pair(q, ev.pair, ev.time);
      if (held == 0) continue;  // a kinematic partner, or both held: the resting solver's
      stats.held += held;
    } else {
      impact(q, ev.pair, ev.time, dt);
      ++stats.impacts;
    }
    if (again >> 16 != budget.polled) {  // a long tick stays stoppable: every 65 536 predictions
      budget.polled = again >> 16;
      throw_if_stop_requested();
    }
    for (const std::uint32_t k : {a, b}) {
      if (discs_[k].dynamic) predict_after(q, tick, k, ev.time, again);
    }
  }
  return true;
}

template <class Real>
bool DiscContacts<Real>::over_budget(ImpactLane& q, ContactStats& stats, std::uint32_t a,
                                     std::uint32_t b, double now) {
  if (q.split) return meet_other_lane(q);  // its share of the cap: the one lane decides
  cap_ = CapHit{"max_tick_predictions", q.budget.cap, a, b, now};
  stats.capped = 1;
  return false;
}

template <class Real>
void DiscContacts<Real>::run_events(const Tick& tick, ContactStats& stats, int windows) {
  const double dt = tick.dt;
  ImpactLane& q = lanes_[0];
  for (const std::uint32_t k : q.held) held_[k].on = held_[k].released = 0;
  q.held.clear();
  if (windows > 1 || !run_lanes(tick, stats)) run_lane(tick, stats, windows);
  // The end of the tick on each disc's last motion; the integrator's velocity is the model's
  // minus the offset δ.
  live_range(0, live_count(), [&](std::uint32_t k) {
    if (!changed_[k]) return;
    const DiscMotion& m = motion_[k];
    const DiscOffset& o = model_offset_[k];
    const double s = dt - m.t;
    ex_[k] = m.px(dt), ey_[k] = m.py(dt);
    if (held_[k].on) {  // where it was held, with the velocity it had there
      evx_[k] = held_[k].ux - o.x, evy_[k] = held_[k].uy - o.y;
    } else {
      evx_[k] = m.ux + s * m.ax - o.x, evy_[k] = m.uy + s * m.ay - o.y;
    }
  });
}

template <class Real>
void DiscContacts<Real>::run_lane(const Tick& tick, ContactStats& stats, int windows) {
  const double dt = tick.dt;
  ImpactLane& q = lanes_[0];
  q.log.clear();
  q.heap.clear();
  q.split = false;
  q.budget = EventBudget{0, 0, max_tick_predictions(discs_.size())};
  for (int w = 0; w < windows; ++w) {
    // Window w of the tick: [t0, horizon_] (the whole tick when windows = 1).
    const double t0 = w == 0 ? 0.0 : dt * w / windows;
    horizon_ = w + 1 == windows ? dt : dt * (w + 1) / windows;
    if (windows > 1) {  // its pairs, by the discs' boxes over it (disc_windows.cpp)
      throw_if_stop_requested();
      window_boxes(tick, t0, horizon_);
      if (!find_candidates(tick, stats, max_candidate_pairs(discs_.size()), false)) break;
      if (w > 0) q.budget.again += pairs_.size();  // their first predictions
    }
    start_reach(q);
    first_events(tick, t0);
    const bool done = run_window(q, tick, stats);
    finish_reach();
    if (!done) break;
  }
}

}  // namespace fixstep::detail
