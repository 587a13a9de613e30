// Segments in the plane pass (world_contacts.cpp): a disc meets each segment near it as the
// local plane of its contact (the closest point's normal, the segment's friction and
// restitution), found at its time of impact by segment_impact() (segment_set.cpp). The
// segments near a disc come from the segment grid, queried with the box the disc can reach in
// the rest of the tick (|v| T + ½ |a| T² + r about its centre). A segment a kinematic body
// carries is where place_segments() put it at the tick's start and moves at its body's velocity
// u through the tick: it is met in its own frame (the disc's motion less u t), and its local
// plane is given where it is at the contact's time, with u, which the caller's impact takes
// as the plane's velocity.
#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "fixstep/core/components.hpp"
#include "fixstep/core/float_mode.hpp"
#include "fixstep/core/limits.hpp"
#include "fixstep/core/segment.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/value_ranges.hpp"
#include "world_kernel.hpp"

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
  if (!(within_coefficient(mu) && mu >= 0.0)) {  // value_ranges.hpp
    throw std::invalid_argument(
        fmt::format("{}: friction must be in [0, 1e100] (got {})", who, mu));
  }
  if (def.body.is_null()) {
    segments_.add(def);
  } else {
    if (!bodies_.contains(def.body) || types_[bodies_.index(def.body)] != BodyType::kinematic) {
      throw std::invalid_argument(fmt::format(
          "{}: body must be a live kinematic body (got {}{})", who, describe(def.body),
          bodies_.contains(def.body)
              ? fmt::format(", a {} one", body_type_name(types_[bodies_.index(def.body)]))
              : std::string()));
    }
    const std::size_t j = bodies_.index(def.body);
    segments_.add_carried(def, Vec2{double(x_[j]), double(y_[j])});
    place_segments();
  }
  terms_dirty_ = true;  // rebuild_contacts() rebuilds the grid
  return segments_.size() - 1;
}

template <class Real>
void detail::WorldKernel<Real>::place_segments() {
  const auto carried = segments_.carried();
  for (std::size_t k = 0; k < carried.size(); ++k) {
    const Entity e = segments_.defs()[carried[k]].body;
    if (!bodies_.contains(e)) {  // its body was destroyed: it stays where it is, static
      segments_.stop(k);
      continue;
    }
    const std::size_t j = bodies_.index(e);
    segments_.place(k, Vec2{double(x_[j]), double(y_[j])}, Vec2{double(vx_[j]), double(vy_[j])});
  }
}

template <class Real>
bool detail::WorldKernel<Real>::segment_overlap(double x, double y, double r, double tol,
                                                double time, Vec2 start, PlaneDef& plane, Vec2& u) {
  segments_.query(x - r, y - r, x + r, y + r, segment_found_);
  segment_tests_ += segment_found_.size();
  double deepest = -tol;
  bool found = false;
  for (const std::uint32_t i : segment_found_) {
    const SegmentShape& s = segments_.shapes()[i];
    const Vec2 v = segments_.velocity(i);  // the disc seen from the segment's frame
    SegmentTouch t;
    if (!segment_touch(s, x - v.x * time, y - v.y * time, t) || !(t.distance - r < deepest) ||
        !segment_acts(s, start.x, start.y, r, t.nx, t.ny, t.distance - r)) {
      continue;
    }
    deepest = t.distance - r;
    // Where it is now; a static segment's offset as it was (adding 0 would turn -0 into +0).
    const double offset = t.offset + (t.nx * v.x + t.ny * v.y) * time;
    plane = PlaneDef{Vec2{t.nx, t.ny}, v.x != 0.0 || v.y != 0.0 ? offset : t.offset, s.restitution,
                     s.friction};
    u = v;
    found = true;
  }
  return found;
}

template <class Real>
double detail::WorldKernel<Real>::first_segment_hit(const SegmentMotion& m, double time, double r,
                                                    double horizon, double rel, double vtol,
                                                    Vec2 start, PlaneDef& plane, Vec2& u,
                                                    std::uint32_t& index, std::uint64_t& looked) {
  const double reach = disc_reach(std::sqrt(m.vx * m.vx + m.vy * m.vy),
                                  std::sqrt(m.ax * m.ax + m.ay * m.ay), horizon, r);
  segments_.query(m.x - reach, m.y - reach, m.x + reach, m.y + reach, segment_found_);
  looked += segment_found_.size();
  segment_tests_ += segment_found_.size();
  const double tol = rel * (std::abs(m.x) + std::abs(m.y) + r);
  double first = std::numeric_limits<double>::infinity();
  for (const std::uint32_t i : segment_found_) {
    const SegmentShape& s = segments_.shapes()[i];
    const Vec2 v = segments_.velocity(i);
    const bool moving = v.x != 0.0 || v.y != 0.0;
    SegmentMotion rel_m = m;  // the disc's motion seen from the segment's frame
    if (moving) {
      rel_m.x -= v.x * time, rel_m.y -= v.y * time, rel_m.vx -= v.x, rel_m.vy -= v.y;
    }
    SegmentTouch t;
    const double when = segment_impact(s, moving ? rel_m : m, r, horizon, tol, vtol, t);
    if (!(when < first) || !segment_acts(s, start.x, start.y, r, t.nx, t.ny, 0.0)) continue;
    first = when, index = i, u = v;
    const double offset = t.offset + (t.nx * v.x + t.ny * v.y) * (time + when);
    plane = PlaneDef{Vec2{t.nx, t.ny}, moving ? offset : t.offset, s.restitution, s.friction};
  }
  return first;
}

}  // namespace fixstep
