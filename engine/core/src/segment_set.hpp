// A world's static segments (SegmentDef) with their derived geometry and a uniform grid of
// their bounding boxes, and the contact geometry discs need of them: the closest feature under
// the ghost-vertex rule, and the time of impact of a disc moving on a parabola. Part of the
// engine's World (segment_set.cpp); not a public interface.
#pragma once

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "fixstep/core/segment.hpp"

namespace fixstep::detail {

/// A segment's geometry as contacts use it (from a SegmentDef), all in double.
struct SegmentShape {
  double ax = 0, ay = 0, bx = 0, by = 0;  ///< ends, m
  double dx = 1, dy = 0;                  ///< unit direction a -> b
  double length = 0;                      ///< |b - a|, m
  double nx = 0, ny = 1;                  ///< unit normal (-dy, dx)
  double pdx = 0, pdy = 0;                ///< unit direction prev -> a (has_prev)
  double restitution = 0, friction = 0;
  bool has_prev = false, has_next = false;
  bool one_way = false;  ///< SegmentDef::one_way: up is the normal (nx, ny)
};

/// Whether segment s acts on a disc of radius r (m) at a contact of unit normal (nx, ny) (from
/// the segment towards the disc's centre) and `separation` (m, < 0: overlap; 0 at a time of
/// impact), the disc's centre having been at (x0, y0) (m, in the segment's frame at the
/// tick's start) when the tick began. Always for a two-sided segment; for a one-way one the
/// rule of one_way.hpp (slop one_way_disc_slop r) holds both for the disc's closest feature
/// at the tick's start (where a neighbour holds it: its height over the segment's line, as if
/// on the face) and for this contact, so a disc that started below, beside an end or half-way
/// through passes, and one that slipped past an end within the tick is not lifted out.
[[nodiscard]] bool segment_acts(const SegmentShape& s, double x0, double y0, double r, double nx,
                                double ny, double separation);

/// Where a disc touches a segment: the contact's unit normal (from the segment to the disc's
/// centre) and the plane through the closest point, n·x = offset (m); `distance` from the
/// centre to the closest point, m.
struct SegmentTouch {
  double nx = 0, ny = 1, offset = 0, distance = 0;
};

/// The closest feature of s to the point (x, y) (m), under the ghost-vertex rule (SegmentDef):
/// false when that feature is a joint vertex outside its own region, or the end b of a
/// segment with a next one (a neighbour covers the point). A point on the segment's line is on
/// its + face (the normal (-dy, dx)).
bool segment_touch(const SegmentShape& s, double x, double y, SegmentTouch& out);

/// A disc's motion over a window: position x + v s + ½ a s² (m) for s in [0, horizon] (s).
struct SegmentMotion {
  double x = 0, y = 0, vx = 0, vy = 0, ax = 0, ay = 0;
};

/// How far from its centre a disc of radius r (m) moving at speed |v| (m/s) with acceleration
/// |a| (m/s²) can reach within `horizon` (s), with a margin for rounding: the half-width of the
/// box a segment query takes, m.
inline double disc_reach(double speed, double accel, double horizon, double r) {
  return (speed + 0.5 * horizon * accel) * horizon * (1.0 + 1e-9) + r * (1.0 + 1e-9);
}

/// The first time s in [0, horizon] at which a disc of radius r (m) moving as m comes into
/// contact with s while approaching, or infinity; `at` gets the contact there. The interior is
/// the disc's face of the line at distance r, its root taken only where the centre projects
/// within [0, length]; an end point is a disc of radius 0 (the quartic of disc_toi.hpp, exact
/// to the last bit), taken only where the ghost-vertex rule keeps it. A disc within `tol` (m) of
/// contact and moving (beyond `vtol`, m/s) or accelerating into it meets it at s = 0, as for
/// planes (world_contacts.cpp).
double segment_impact(const SegmentShape& s, const SegmentMotion& m, double r, double horizon,
                      double tol, double vtol, SegmentTouch& at);

/// The segments of a world in creation order and a uniform grid of their bounding boxes, so
/// that a disc tests only the segments near it. Cells are the mean of the static segments'
/// larger box sides; a segment spanning more than max_cells_per_segment cells, and every
/// segment a kinematic body carries (SegmentDef::body), is tested by every query. A carried
/// segment is where place() last put it, with the velocity place() gave it.
class SegmentSet {
 public:
  static constexpr std::size_t max_cells_per_segment = 64;
  /// Appends a checked definition (WorldKernel::add_segment validates it); the grid is stale
  /// until build().
  void add(const SegmentDef& def);
  /// Appends a segment carried by a kinematic body whose position is `origin` (m) now.
  void add_carried(const SegmentDef& def, Vec2 origin);
  /// The carried segments' indices, in creation order.
  [[nodiscard]] std::span<const std::uint32_t> carried() const { return carried_; }
  /// Puts carried segment carried()[k] where its body at `position` (m) puts it, moving at
  /// `velocity` (m/s) until the next place(). Nothing is rebuilt: every query tests it.
  void place(std::size_t k, Vec2 position, Vec2 velocity);
  /// Leaves carried segment carried()[k] where it is, at rest (its body is gone).
  void stop(std::size_t k) { velocity_[carried_[k]] = Vec2{}; }
  /// Segment i's velocity (m/s): 0 for a static one.
  [[nodiscard]] Vec2 velocity(std::uint32_t i) const {
    return velocity_.empty() ? Vec2{} : velocity_[i];
  }
  /// Whether some segment is carried.
  [[nodiscard]] bool moves() const { return !carried_.empty(); }
  /// Rebuilds the grid of the segments added so far.
  void build();
  [[nodiscard]] bool empty() const { return defs_.empty(); }
  [[nodiscard]] std::size_t size() const { return defs_.size(); }
  [[nodiscard]] std::span<const SegmentDef> defs() const { return defs_; }
  [[nodiscard]] std::span<const SegmentShape> shapes() const { return shapes_; }
  /// The indices of the segments whose boxes may meet the box [x0, x1] × [y0, y1] (m),
  /// ascending and without repeats, into out (cleared first). Needs build() after the last add.
  void query(double x0, double y0, double x1, double y1, std::vector<std::uint32_t>& out) const;
  /// Heap bytes (snapshot_bytes).
  [[nodiscard]] std::size_t bytes() const;

 private:
  [[nodiscard]] std::int64_t cell(double v) const;
  std::vector<SegmentDef> defs_;
  std::vector<SegmentShape> shapes_;
  double cell_ = 1.0;                                          ///< m
  std::vector<std::pair<std::uint64_t, std::uint32_t>> grid_;  ///< (cell key, segment), sorted
  std::vector<std::uint32_t> big_;                             ///< segments in every query
  // Carried segments: their indices, definitions where they were added and their bodies'
  // positions then; every segment's velocity (empty while none is carried).
  std::vector<std::uint32_t> carried_;
  std::vector<SegmentDef> carried_def_;
  std::vector<Vec2> carried_origin_;
  std::vector<Vec2> velocity_;
};

}  // namespace fixstep::detail
