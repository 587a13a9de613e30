// Static segments in the plane pass (world_contacts.cpp): a disc meets each segment near it as
// the local plane of its contact (the closest point's normal, the segment's friction and
// restitution), found at its time of impact by segment_impact() (segment_set.cpp). The
// segments near a disc come from the segment grid, queried with the box the disc can reach in
// the rest of the tick (|v| T + ½ |a| T² + r about its centre).
#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "fixstep/detail/world_kernel.hpp"
#include "fixstep/float_mode.hpp"
#include "fixstep/limits.hpp"

namespace fixstep {

template <class Real>
std::size_t detail::WorldKernel<Real>::add_segment(const SegmentDef& def) {
  const IeeeFloatMode ieee;  // a state never depends on the caller's FPU mode (float_mode.hpp)
  const std::string who = fmt::format("segment[{}]", segments_.size());
  auto finite = [&](Vec2 v, const char* field) {
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(static_cast<Real>(v.x)) ||
        !std::isfinite(static_cast<Real>(v.y)) || !(std::abs(v.x) <= max_state_magnitude) ||
        !(std::abs(v.y) <= max_state_magnitude)) {
      throw std::invalid_argument(fmt::format("{}: {} must be finite, within {:g} m (got [{}, {}])",
                                              who, field, max_state_magnitude, v.x, v.y));
    }
  };
  finite(def.a, "a");
  finite(def.b, "b");
  if (def.prev) finite(*def.prev, "prev");
  if (def.next) finite(*def.next, "next");
  if (def.a == def.b) {
    throw std::invalid_argument(
        fmt::format("{}: a and b must differ (both are [{}, {}])", who, def.a.x, def.a.y));
  }
  const double e = def.restitution, mu = def.friction;
  if (!(std::isfinite(e) && e >= 0.0 && e <= 1.0)) {
    throw std::invalid_argument(fmt::format("{}: restitution must be in [0, 1] (got {})", who, e));
  }
  if (!(std::isfinite(mu) && mu >= 0.0)) {
    throw std::invalid_argument(
        fmt::format("{}: friction must be finite and >= 0 (got {})", who, mu));
  }
  segments_.add(def);
  terms_dirty_ = true;  // rebuild_contacts() rebuilds the grid
  return segments_.size() - 1;
}

template <class Real>
bool detail::WorldKernel<Real>::segment_overlap(double x, double y, double r, double tol,
                                                PlaneDef& plane) {
  segments_.query(x - r, y - r, x + r, y + r, segment_found_);
  double deepest = -tol;
  bool found = false;
  for (const std::uint32_t i : segment_found_) {
    const SegmentShape& s = segments_.shapes()[i];
    SegmentTouch t;
    if (!segment_touch(s, x, y, t) || !(t.distance - r < deepest)) continue;
    deepest = t.distance - r;
    plane = PlaneDef{Vec2{t.nx, t.ny}, t.offset, s.restitution, s.friction};
    found = true;
  }
  return found;
}

template <class Real>
double detail::WorldKernel<Real>::first_segment_hit(const SegmentMotion& m, double r,
                                                    double horizon, double rel, double vtol,
                                                    PlaneDef& plane, std::uint32_t& index,
                                                    std::uint64_t& looked) {
  const double reach = (std::sqrt(m.vx * m.vx + m.vy * m.vy) +
                        0.5 * horizon * std::sqrt(m.ax * m.ax + m.ay * m.ay)) *
                           horizon * (1.0 + 1e-9) +
                       r * (1.0 + 1e-9);
  segments_.query(m.x - reach, m.y - reach, m.x + reach, m.y + reach, segment_found_);
  looked += segment_found_.size();
  const double tol = rel * (std::abs(m.x) + std::abs(m.y) + r);
  double first = std::numeric_limits<double>::infinity();
  for (const std::uint32_t i : segment_found_) {
    const SegmentShape& s = segments_.shapes()[i];
    SegmentTouch t;
    const double when = segment_impact(s, m, r, horizon, tol, vtol, t);
    if (!(when < first)) continue;
    first = when, index = i;
    plane = PlaneDef{Vec2{t.nx, t.ny}, t.offset, s.restitution, s.friction};
  }
  return first;
}

#define FIXSTEP_INSTANTIATE(Real)                                                                 \
  template std::size_t detail::WorldKernel<Real>::add_segment(const SegmentDef&);                 \
  template bool detail::WorldKernel<Real>::segment_overlap(double, double, double, double,        \
                                                           PlaneDef&);                            \
  template double detail::WorldKernel<Real>::first_segment_hit(const SegmentMotion&, double,      \
                                                               double, double, double, PlaneDef&, \
                                                               std::uint32_t&, std::uint64_t&);
FIXSTEP_INSTANTIATE(float)
FIXSTEP_INSTANTIATE(double)
#undef FIXSTEP_INSTANTIATE

}  // namespace fixstep
