// A RenderFrame taken from a World (frame_data.hpp).
#include "fixstep/render/frame_data.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "fixstep/core/components.hpp"
#include "fixstep/core/joint.hpp"
#include "fixstep/core/segment.hpp"
#include "fixstep/core/shape.hpp"
#include "fixstep/core/world_settings.hpp"

namespace fixstep {

namespace {

/// `shape` of body entry `body` as drawn (RenderFrame::Shape): its outline (shape_outline's
/// points) and mark in the body frame, less the body's centre of mass `center`. The mark: a
/// circle's rim on its x axis; a box's point min(hx, hy) along its x axis (its side for a
/// square, as short for a long box); a capsule's or polygon's first vertex.
RenderFrame::Shape drawn_shape(const ShapeDef& shape, Vec2 center, std::uint32_t body) {
  RenderFrame::Shape d;
  d.body = body;
  d.radius = static_cast<float>(shape.radius);
  const ShapeOutline outline = shape_outline(shape, Vec2{-center.x, -center.y}, 0.0);
  d.count = static_cast<std::uint32_t>(std::clamp(outline.count, 0, max_polygon_vertices));
  for (std::size_t k = 0; k < d.count; ++k) {
    d.px[k] = static_cast<float>(outline.points[k].x);
    d.py[k] = static_cast<float>(outline.points[k].y);
  }
  Vec2 mark = shape.vertices[0];  // in the shape's frame
  if (shape.kind == ShapeKind::circle) mark = {shape.radius, 0.0};
  if (shape.kind == ShapeKind::box)
    mark = {std::min(shape.half_extents.x, shape.half_extents.y), 0.0};
  const double c = std::cos(shape.angle), s = std::sin(shape.angle);
  d.mark_x = static_cast<float>(shape.offset.x + (c * mark.x - s * mark.y) - center.x);
  d.mark_y = static_cast<float>(shape.offset.y + (s * mark.x + c * mark.y) - center.y);
  d.color = shape.color;
  return d;
}

/// Body entry j's sprite (appearance `a`, its sprite set) as drawn: sprite_size, or else the
/// bounds of its shapes in `shapes` (those of entry j, body frame less the centre of mass) or
/// its disc's diameter; centred on those bounds or the body.
void fill_sprite(const Appearance& a, std::span<const RenderFrame::Shape> shapes, std::uint32_t j,
                 RenderFrame::Sprite& out) {
  out.body = j;
  out.path.assign(a.sprite);
  float x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool any = false;
  // shapes are in body order: entry j's are one run
  const auto first =
      std::lower_bound(shapes.begin(), shapes.end(), j,
                       [](const RenderFrame::Shape& s, std::uint32_t b) { return s.body < b; });
  for (auto it = first; it != shapes.end() && it->body == j; ++it) {
    const RenderFrame::Shape& s = *it;
    for (std::size_t k = 0; k < s.count; ++k) {
      const float lx = s.px[k] - s.radius, hx = s.px[k] + s.radius;
      const float ly = s.py[k] - s.radius, hy = s.py[k] + s.radius;
      x0 = any ? std::min(x0, lx) : lx, x1 = any ? std::max(x1, hx) : hx;
      y0 = any ? std::min(y0, ly) : ly, y1 = any ? std::max(y1, hy) : hy;
      any = true;
    }
  }
  if (!any) {
    const auto r = static_cast<float>(a.radius);
    x0 = y0 = -r, x1 = y1 = r;
  }
  out.cx = 0.5f * (x0 + x1), out.cy = 0.5f * (y0 + y1);
  const bool sized = a.sprite_size.x > 0.0 && a.sprite_size.y > 0.0;
  out.width = sized ? static_cast<float>(a.sprite_size.x) : x1 - x0;
  out.height = sized ? static_cast<float>(a.sprite_size.y) : y1 - y0;
}

/// Where a joint's end is drawn: its body's centre of mass at the tick (`now`) and where x / y
/// draw it (`drawn`), and the angle its shapes are turned back by, (1 - α) ω dt; the world's
/// ends stay put.
struct EndPose {
  bool on_body = false;
  Vec2 now{}, drawn{};
  double back = 0.0;  ///< rad
  [[nodiscard]] Vec2 turned(Vec2 v) const {
    if (back == 0.0) return v;
    const double c = std::cos(back), s = std::sin(back);
    return {c * v.x + s * v.y, -s * v.x + c * v.y};
  }
  /// A point the body carries, at the frame's moment: its offset from the centre turned back.
  [[nodiscard]] Vec2 moved(Vec2 p) const { return on_body ? drawn + turned(p - now) : p; }
};

/// The frame's joints (RenderFrame::JointMark), after its bodies: each joint's anchors, axis
/// and value from World::joint_state, moved to the frame's moment with their bodies; its type
/// and limits (World::joint) kept per handle.
void fill_joints(const World& world, double alpha, RenderFrame& out) {
  using Mark = RenderFrame::JointMark;
  const std::span<const Joint> joints = world.joints();
  const bool reread = world.tick() < out.tick;  // out.tick: the frame's previous tick
  out.joints.resize(joints.size());
  if (joints.empty()) return;
  const double dt = world.settings().dt;
  bool mapped = false;  // out.entry_of_slot built for this frame's bodies
  auto entry_of = [&](Entity e, std::uint32_t cached) -> std::uint32_t {
    if (e.is_null()) return Mark::world;
    if (cached < out.ids.size() && out.ids[cached] == e) return cached;
    if (!mapped) {  // a body created or destroyed since the joint's last frame
      std::uint32_t slots = 0;
      for (const Entity id : out.ids) slots = std::max(slots, id.index1);
      out.entry_of_slot.assign(slots, Mark::world);
      for (std::size_t j = 0; j < out.ids.size(); ++j)
        out.entry_of_slot[out.ids[j].slot()] = static_cast<std::uint32_t>(j);
      mapped = true;
    }
    const std::uint32_t j =
        e.slot() < out.entry_of_slot.size() ? out.entry_of_slot[e.slot()] : Mark::world;
    return j != Mark::world && out.ids[j] == e ? j : Mark::world;
  };
  auto pose = [&](Entity e, std::uint32_t j) {
    EndPose p;
    if (j == Mark::world) return p;
    const Body b = world.body(e);
    const Vec2 c = world.local_center(e);
    const double cos_t = std::cos(b.angle), sin_t = std::sin(b.angle);
    p.on_body = true;
    p.now = {b.position.x + cos_t * c.x - sin_t * c.y, b.position.y + sin_t * c.x + cos_t * c.y};
    p.drawn = {out.x[j], out.y[j]};
    p.back = (1.0 - alpha) * b.angular_velocity * dt;
    return p;
  };
  for (std::size_t i = 0; i < joints.size(); ++i) {
    Mark& m = out.joints[i];
    if (reread || m.joint != joints[i]) {
      const JointDef def = world.joint(joints[i]);
      m = Mark{};
      m.joint = joints[i];
      m.id_a = def.body_a, m.id_b = def.body_b;
      m.type = def.type;
      m.rope = def.type == JointType::distance && (def.lower || def.upper);
      m.has_lower = def.lower.has_value(), m.has_upper = def.upper.has_value();
      m.lower = static_cast<float>(def.lower.value_or(0.0));
      m.upper = static_cast<float>(def.upper.value_or(0.0));
    }
    const JointState st = world.joint_state(joints[i]);
    m.broken = st.broken;
    if (m.broken) continue;
    m.body_a = entry_of(m.id_a, m.body_a);
    m.body_b = entry_of(m.id_b, m.body_b);
    const EndPose pa = pose(m.id_a, m.body_a), pb = pose(m.id_b, m.body_b);
    const Vec2 a = pa.moved(st.anchor_a), b = pb.moved(st.anchor_b), axis = pa.turned(st.axis);
    m.ax = static_cast<float>(a.x), m.ay = static_cast<float>(a.y);
    m.bx = static_cast<float>(b.x), m.by = static_cast<float>(b.y);
    m.axis_x = static_cast<float>(axis.x), m.axis_y = static_cast<float>(axis.y);
    double value = st.value;
    if (m.type != JointType::revolute) {
      m.value = static_cast<float>(value);
      continue;
    }
    // Revolute: the relative angle θ_b − θ_a − θ_ref turns back with both bodies; the
    // direction from the anchor to the turning body's centre (B's, or A's when B is the world,
    // where the angle grows the other way) sets where the angle 0 lies, turning with the other.
    value -= pb.back - pa.back;
    const bool b_turns = pb.on_body;
    const EndPose& mover = b_turns ? pb : pa;
    const Vec2 pivot = b_turns ? b : a, d = mover.drawn - pivot;
    const double sense = b_turns ? 1.0 : -1.0;
    double direction = 0.0;  // rad: from the anchor to the mover's centre
    if (std::hypot(d.x, d.y) > 1e-6 * (1.0 + std::hypot(pivot.x, pivot.y))) {
      direction = std::atan2(d.y, d.x);
    } else {  // its centre on the anchor (a wheel on an axle): its angle
      const std::uint32_t j = b_turns ? m.body_b : m.body_a;
      direction = j < out.angle.size() ? double(out.angle[j]) : 0.0;
    }
    m.value = static_cast<float>(value);
    m.zero_angle =
        static_cast<float>(std::remainder(direction - sense * value, 2 * std::numbers::pi));
    m.sense = static_cast<float>(sense);
  }
}

}  // namespace

void fill_render_frame(const World& world, double alpha, RenderFrame& out) {
  const std::span<const Entity> bodies = world.bodies();
  const std::size_t n = bodies.size();
  out.x.resize(n);
  out.y.resize(n);
  world.interpolate_positions(alpha, out.x, out.y);
  out.ids.assign(bodies.begin(), bodies.end());
  out.radius.resize(n);
  out.color.resize(n);
  out.visible.resize(n);
  out.trail_time.resize(n);
  out.springs.clear();
  // Bodies with shapes: drawn as their shapes, turned by their angle.
  out.shapes.clear();
  for (std::size_t j = 0; j < n; ++j) {
    const std::span<const ShapeDef> shapes = world.shapes(bodies[j]);
    if (shapes.empty()) continue;
    const Vec2 center = world.local_center(bodies[j]);
    for (const ShapeDef& shape : shapes) {
      out.shapes.push_back(drawn_shape(shape, center, static_cast<std::uint32_t>(j)));
    }
  }
  const auto& contacts = world.settings().contacts;
  const bool rolling = contacts && contacts->rolling;
  out.spin_marks = rolling;
  out.angle.resize(rolling || !out.shapes.empty() ? n : 0);
  out.asleep.resize(contacts && contacts->sleep ? n : 0);
  std::size_t sprites = 0;  // out.sprites[0, sprites) are this frame's (their storage kept)
  for (std::size_t j = 0; j < n; ++j) {
    const Entity e = bodies[j];
    if (const std::optional<Appearance> a = world.get<Appearance>(e)) {
      if (!a->sprite.empty()) {
        if (sprites == out.sprites.size()) out.sprites.emplace_back();
        fill_sprite(*a, out.shapes, static_cast<std::uint32_t>(j), out.sprites[sprites++]);
      }
      out.radius[j] = static_cast<float>(a->radius);
      out.color[j] = a->color;
      out.visible[j] = a->visible ? 1 : 0;
      out.trail_time[j] = a->trail ? static_cast<float>(a->trail_time) : 0.0f;
    } else {
      out.radius[j] = 0.0f;
      out.color[j] = Rgba8{0, 0, 0, 0};
      out.visible[j] = 1;
      out.trail_time[j] = static_cast<float>(default_trail_time);
    }
    if (!out.angle.empty()) {  // θ at the frame's moment: the tick's θ less (1 - α) ω dt
      const Body b = world.body(e);
      const double back = (1.0 - alpha) * b.angular_velocity * world.settings().dt;
      // A body with shapes may have turned many times (|θ| up to 1e12): within one turn
      // first, for float to keep its angle to the pixel.
      const double angle = out.shapes.empty()
                               ? b.angle - back
                               : std::remainder(b.angle - back, 2 * std::numbers::pi);
      out.angle[j] = static_cast<float>(angle);
    }
    if (!out.asleep.empty()) out.asleep[j] = world.asleep(e) ? 1 : 0;
    if (const std::optional<SpringDamper> s = world.get<SpringDamper>(e)) {
      out.springs.push_back({static_cast<float>(s->anchor.x), static_cast<float>(s->anchor.y),
                             static_cast<std::uint32_t>(j)});
    }
  }
  out.sprites.resize(sprites);
  const std::size_t links = world.link_count();
  out.link_a.resize(links);
  out.link_b.resize(links);
  world.link_ends(out.link_a, out.link_b);
  out.planes.assign(world.planes().begin(), world.planes().end());
  out.segments.assign(world.segments().begin(), world.segments().end());
  for (SegmentDef& s : out.segments) {  // a carried one where its body is at the frame's moment
    if (s.body.is_null() || !world.contains(s.body)) continue;
    const Vec2 v = world.body(s.body).velocity;
    const double back = (1.0 - alpha) * world.settings().dt;
    const auto moved = [&](Vec2 p) { return Vec2{p.x - v.x * back, p.y - v.y * back}; };
    s.a = moved(s.a), s.b = moved(s.b);
    if (s.prev) s.prev = moved(*s.prev);
    if (s.next) s.next = moved(*s.next);
  }
  fill_joints(world, alpha, out);
  out.tick = world.tick();
  out.dt = world.settings().dt;
  out.alpha = alpha;
}

}  // namespace fixstep
