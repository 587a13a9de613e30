// Static segments: their geometry, grid, closest features under the ghost-vertex rule and
// times of impact (segment_set.hpp).
#include "segment_set.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "copy_bytes.hpp"
#include "disc_toi.hpp"
#include "one_way.hpp"

namespace fixstep {

std::vector<SegmentDef> polyline_segments(std::span<const Vec2> points, double restitution,
                                          double friction, bool closed) {
  const std::size_t n = points.size();
  if (n < (closed ? 3u : 2u)) {
    throw std::invalid_argument(
        fmt::format("polyline: needs at least {} points (got {})", closed ? 3 : 2, n));
  }
  const std::size_t count = closed ? n : n - 1;
  std::vector<SegmentDef> out(count);
  for (std::size_t i = 0; i < count; ++i) {
    SegmentDef& s = out[i];
    s.a = points[i], s.b = points[(i + 1) % n];
    if (s.a == s.b) {
      throw std::invalid_argument(
          fmt::format("polyline: segment {} has zero length (points {} and {} are both [{}, {}])",
                      i, i, (i + 1) % n, s.a.x, s.a.y));
    }
    s.restitution = restitution, s.friction = friction;
    if (closed || i > 0) s.prev = points[(i + n - 1) % n];
    if (closed || i + 1 < count) s.next = points[(i + 2) % n];
  }
  return out;
}

namespace detail {

namespace {

double seg_length(double x, double y) {
  return std::sqrt(x * x + y * y);  // correctly rounded (std::hypot differs between libms)
}

/// The first s in [0, horizon] where g(s) = g0 + b s + ½ c s² falls to 0 while approaching
/// (b + c s <= 0), or infinity; within tol of contact (g0 <= tol): 0 when moving (beyond
/// vtol) or accelerating (beyond atol, m/s²) in, else -2b/c when it leaves and falls back.
/// (A disc resting on a sloped segment has its normal acceleration cancelled up to rounding,
/// ~1e-15 |a|: without atol that rounding would be an impact at 0 again and again.) The planes'
/// rule (world_contacts.cpp), roots by disc_toi.hpp's cancellation-free quadratic.
double line_impact(double g0, double b, double c, double horizon, double tol, double vtol,
                   double atol) {
  constexpr double none = std::numeric_limits<double>::infinity();
  if (g0 <= tol) {
    if (b < -vtol || (b <= vtol && c < -atol)) return 0.0;
    // Leaving (b > 0) and falling back; a rest (b <= 0 here) within the tolerances has no event
    // (-2b/c would be a time before now).
    return c < 0.0 && b > 0.0 && -2.0 * b / c <= horizon ? -2.0 * b / c : none;
  }
  double roots[2] = {none, none};
  const int n = quadratic_roots(g0, b, 0.5 * c, -1e-300, horizon * (1.0 + 1e-15), roots);
  for (int i = 0; i < n; ++i) {
    const double s = std::min(std::max(roots[i], 0.0), horizon);
    if (b + c * s <= 0.0) return s;
  }
  return none;
}

}  // namespace

bool segment_touch(const SegmentShape& s, double x, double y, SegmentTouch& out) {
  const double wx = x - s.ax, wy = y - s.ay;
  const double t = s.dx * wx + s.dy * wy;
  const double h = s.nx * wx + s.ny * wy;
  const double side = h >= 0.0 ? 1.0 : -1.0;
  if (t >= 0.0 && t <= s.length) {
    out.nx = side * s.nx, out.ny = side * s.ny;
    out.offset = out.nx * s.ax + out.ny * s.ay;
    out.distance = std::abs(h);
    return true;
  }
  double px = s.bx, py = s.by;
  if (t < 0.0) {
    // A joint's vertex: only in its own region, past the end of the segment before it.
    if (s.has_prev && !(s.pdx * wx + s.pdy * wy > 0.0)) return false;
    px = s.ax, py = s.ay;
  } else if (s.has_next) {
    return false;  // the joint's vertex belongs to the next segment
  }
  const double ex = x - px, ey = y - py;
  const double d = seg_length(ex, ey);
  out.nx = d > 0.0 ? ex / d : side * s.nx, out.ny = d > 0.0 ? ey / d : side * s.ny;
  out.offset = out.nx * px + out.ny * py;
  out.distance = d;
  return true;
}

double segment_impact(const SegmentShape& s, const SegmentMotion& m, double r, double horizon,
                      double tol, double vtol, SegmentTouch& at) {
  constexpr double none = std::numeric_limits<double>::infinity();
  double first = none;
  auto position = [&m](double t, double& x, double& y) {
    x = m.x + m.vx * t + 0.5 * m.ax * t * t, y = m.y + m.vy * t + 0.5 * m.ay * t * t;
  };
  // Rounding of a cancelled normal acceleration (a few ulps of |a|).
  const double atol =
      64.0 * std::numeric_limits<double>::epsilon() * std::sqrt(m.ax * m.ax + m.ay * m.ay);
  // The interior: the face the centre is on.
  {
    const double h = s.nx * (m.x - s.ax) + s.ny * (m.y - s.ay);
    const double side = h >= 0.0 ? 1.0 : -1.0;
    const double nx = side * s.nx, ny = side * s.ny;
    const double t = line_impact(std::abs(h) - r, nx * m.vx + ny * m.vy, nx * m.ax + ny * m.ay,
                                 horizon, tol, vtol, atol);
    double x = 0, y = 0;
    position(std::isfinite(t) ? t : 0.0, x, y);
    const double along = s.dx * (x - s.ax) + s.dy * (y - s.ay);
    if (t < first && along >= 0.0 && along <= s.length) {
      first = t;
      at = SegmentTouch{nx, ny, nx * s.ax + ny * s.ay, r};
    }
  }
  // The end points (b only without a next segment: a joint's vertex is the next one's a).
  for (int end = 0; end < (s.has_next ? 1 : 2); ++end) {
    const double px = end == 0 ? s.ax : s.bx, py = end == 0 ? s.ay : s.by;
    const double ex = m.x - px, ey = m.y - py, d = seg_length(ex, ey);
    double t = none;
    if (d - r <= tol) {
      if (d > 0.0) {
        const double b = (ex * m.vx + ey * m.vy) / d, c = (ex * m.ax + ey * m.ay) / d;
        if (b < -vtol || (b <= vtol && c < -atol)) t = 0.0;
      }
    } else {
      t = first_contact(RelativeMotion{ex, ey, m.vx, m.vy, m.ax, m.ay, r}, horizon);
    }
    if (!(t < first)) continue;
    double x = 0, y = 0;
    position(t, x, y);
    SegmentTouch touch;
    if (!segment_touch(s, x, y, touch) || touch.distance > r * (1.0 + 1e-9) + tol) continue;
    // The closest feature there must be this end point (not the interior or a ghosted joint).
    const double along = s.dx * (x - s.ax) + s.dy * (y - s.ay);
    if (end == 0 ? !(along < 0.0) : !(along > s.length)) continue;
    first = t;
    at = touch;
  }
  return first;
}

bool segment_acts(const SegmentShape& s, double x0, double y0, double r, double nx, double ny,
                  double separation) {
  if (!s.one_way) return true;
  const Vec2 up = one_way_segment_up(s.dx, s.dy);
  const double slop = one_way_disc_slop * r;
  // Where the disc was at the tick's start: its closest feature there (or, where a
  // neighbour's feature holds it, the segment's line).
  SegmentTouch start;
  if (!segment_touch(s, x0, y0, start)) {
    start = SegmentTouch{up.x, up.y, 0.0, (x0 - s.ax) * up.x + (y0 - s.ay) * up.y};
  }
  return one_way_blocks(up, Vec2{start.nx, start.ny}, start.distance - r, slop) &&
         one_way_blocks(up, Vec2{nx, ny}, separation, slop);
}

namespace {
SegmentShape shape_of(const SegmentDef& def) {
  SegmentShape s;
  s.ax = def.a.x, s.ay = def.a.y, s.bx = def.b.x, s.by = def.b.y;
  s.length = seg_length(s.bx - s.ax, s.by - s.ay);
  s.dx = (s.bx - s.ax) / s.length, s.dy = (s.by - s.ay) / s.length;
  s.nx = -s.dy, s.ny = s.dx;
  if (def.prev) {
    const double px = s.ax - def.prev->x, py = s.ay - def.prev->y;
    const double len = seg_length(px, py);
    s.has_prev = len > 0.0;
    s.pdx = s.has_prev ? px / len : 0.0, s.pdy = s.has_prev ? py / len : 0.0;
  }
  s.has_next = def.next.has_value() && !(*def.next == def.b);
  s.restitution = def.restitution, s.friction = def.friction;
  s.one_way = def.one_way;
  return s;
}
}  // namespace

void SegmentSet::add(const SegmentDef& def) {
  defs_.push_back(def);
  shapes_.push_back(shape_of(def));
  if (!velocity_.empty()) velocity_.emplace_back();
}

void SegmentSet::add_carried(const SegmentDef& def, Vec2 origin) {
  carried_.push_back(static_cast<std::uint32_t>(defs_.size()));
  carried_def_.push_back(def);
  carried_origin_.push_back(origin);
  add(def);
  velocity_.resize(defs_.size());
}

void SegmentSet::place(std::size_t k, Vec2 position, Vec2 velocity) {
  const std::uint32_t i = carried_[k];
  const SegmentDef& at = carried_def_[k];
  const double dx = position.x - carried_origin_[k].x, dy = position.y - carried_origin_[k].y;
  const auto moved = [&](Vec2 p) { return Vec2{p.x + dx, p.y + dy}; };
  SegmentDef& d = defs_[i];
  d.a = moved(at.a), d.b = moved(at.b);
  if (at.prev) d.prev = moved(*at.prev);
  if (at.next) d.next = moved(*at.next);
  shapes_[i] = shape_of(d);
  velocity_[i] = velocity;
}

std::int64_t SegmentSet::cell(double v) const {
  constexpr double limit = 1073741824.0;  // 2^30: far cells share the last one
  const double c = std::floor(v / cell_);
  return static_cast<std::int64_t>(std::min(std::max(c, -limit), limit));
}

namespace {
std::uint64_t cell_key(std::int64_t ix, std::int64_t iy) {
  return (std::uint64_t(std::uint32_t(ix)) << 32) | std::uint32_t(iy);
}
}  // namespace

void SegmentSet::build() {
  grid_.clear(), big_.clear();
  if (shapes_.empty()) return;
  double sum = 0.0;
  std::size_t fixed = 0;
  for (std::uint32_t i = 0; i < shapes_.size(); ++i) {
    if (!defs_[i].body.is_null()) continue;  // carried: in every query
    const SegmentShape& s = shapes_[i];
    sum += std::max(std::abs(s.bx - s.ax), std::abs(s.by - s.ay));
    ++fixed;
  }
  cell_ = fixed ? std::max(sum / double(fixed), 1e-6) : 1.0;
  for (std::uint32_t i = 0; i < shapes_.size(); ++i) {
    const SegmentShape& s = shapes_[i];
    if (!defs_[i].body.is_null()) {
      big_.push_back(i);
      continue;
    }
    const std::int64_t x0 = cell(std::min(s.ax, s.bx)), x1 = cell(std::max(s.ax, s.bx));
    const std::int64_t y0 = cell(std::min(s.ay, s.by)), y1 = cell(std::max(s.ay, s.by));
    if (double(x1 - x0 + 1) * double(y1 - y0 + 1) > double(max_cells_per_segment)) {
      big_.push_back(i);
      continue;
    }
    for (std::int64_t ix = x0; ix <= x1; ++ix) {
      for (std::int64_t iy = y0; iy <= y1; ++iy) grid_.emplace_back(cell_key(ix, iy), i);
    }
  }
  std::sort(grid_.begin(), grid_.end());
}

void SegmentSet::query(double x0, double y0, double x1, double y1,
                       std::vector<std::uint32_t>& out) const {
  out.clear();
  const std::int64_t cx0 = cell(x0), cx1 = cell(x1), cy0 = cell(y0), cy1 = cell(y1);
  if (!(x0 <= x1 && y0 <= y1) ||
      double(cx1 - cx0 + 1) * double(cy1 - cy0 + 1) > double(grid_.size())) {
    for (std::uint32_t i = 0; i < shapes_.size(); ++i) out.push_back(i);  // a wide box: all
    return;
  }
  for (std::int64_t ix = cx0; ix <= cx1; ++ix) {
    for (std::int64_t iy = cy0; iy <= cy1; ++iy) {
      const std::uint64_t key = cell_key(ix, iy);
      auto it = std::lower_bound(grid_.begin(), grid_.end(), std::make_pair(key, 0u));
      for (; it != grid_.end() && it->first == key; ++it) out.push_back(it->second);
    }
  }
  out.insert(out.end(), big_.begin(), big_.end());
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

std::size_t SegmentSet::bytes() const {
  return copy_bytes(defs_, shapes_, grid_, big_, carried_, carried_def_, carried_origin_,
                    velocity_);
}

}  // namespace detail
}  // namespace fixstep
