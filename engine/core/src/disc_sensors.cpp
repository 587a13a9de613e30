// Disc contacts: which candidate pairs reach the narrowphase (links and collision filters), and
// what sensors see. A sensor (Collider::sensor) is a disc of the broadphase that no contact
// resolves: after the tick, each pair of a sensor and a disc it may sense overlaps when their
// centres end the tick closer than r_a + r_b, and crossed when they did not overlap at the
// tick's start nor its end but the straight relative path from one to the other comes closer
// (a ball falling through a thin sensor within one tick). The path between the two states is
// taken as straight; contacts bend it only within the tick, and a sensor reports no more than
// whether a disc got in.
#include <algorithm>
#include <cmath>

#include "disc_contacts.hpp"

namespace fixstep::detail {

template <class Real>
void DiscContacts<Real>::sort_out_pairs() {
  std::size_t keep = 0;
  for (const DiscPair p : pairs_) {
    if (!linked_.empty()) {
      if (std::binary_search(linked_.begin(), linked_.end(), pair_key(p))) continue;
    }
    if (!filters_.empty()) {
      if (!should_collide(filters_[p.a], filters_[p.b])) continue;
      const bool sa = discs_[p.a].sensor != 0, sb = discs_[p.b].sensor != 0;
      if (sa || sb) {
        if (sa != sb) sensor_pairs_.push_back(p);  // a sensor never senses a sensor
        continue;
      }
    }
    pairs_[keep++] = p;
  }
  pairs_.resize(keep);
}

template <class Real>
void DiscContacts<Real>::detect_sensors(const Tick& tick) {
  for (const DiscPair p : sensor_pairs_) {
    const Disc &da = discs_[p.a], &db = discs_[p.b];
    const double reach = da.radius + db.radius, reach2 = reach * reach;
    const double x1 = double(tick.x[da.body]) - double(tick.x[db.body]);
    const double y1 = double(tick.y[da.body]) - double(tick.y[db.body]);
    std::uint8_t crossed = 0;
    if (!std::isless(x1 * x1 + y1 * y1, reach2)) {  // quiet for NaN (a faulted state)
      const double x0 = double(x0_[p.a]) - double(x0_[p.b]);
      const double y0 = double(y0_[p.a]) - double(y0_[p.b]);
      if (std::isless(x0 * x0 + y0 * y0, reach2)) continue;  // it left: the event list sees it go
      const double ex = x1 - x0, ey = y1 - y0, len2 = ex * ex + ey * ey;
      if (!std::isgreater(len2, 0.0)) continue;
      const double s = std::clamp(-(x0 * ex + y0 * ey) / len2, 0.0, 1.0);
      const double cx = x0 + s * ex, cy = y0 + s * ey;
      if (!std::isless(cx * cx + cy * cy, reach2)) continue;
      crossed = 1;
    }
    const bool a_senses = da.sensor != 0;
    sensed_.push_back(
        SensorOverlap{a_senses ? da.body : db.body, a_senses ? db.body : da.body, crossed});
  }
}

}  // namespace fixstep::detail
