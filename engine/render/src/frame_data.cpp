// A RenderFrame taken from a World (frame_data.hpp).
#include "fixstep/render/frame_data.hpp"

#include <optional>

#include "fixstep/core/components.hpp"
#include "fixstep/core/segment.hpp"
#include "fixstep/core/world_settings.hpp"

namespace fixstep {

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
  const auto& contacts = world.settings().contacts;
  out.angle.resize(contacts && contacts->rolling ? n : 0);
  out.asleep.resize(contacts && contacts->sleep ? n : 0);
  for (std::size_t j = 0; j < n; ++j) {
    const Entity e = bodies[j];
    if (const std::optional<Appearance> a = world.get<Appearance>(e)) {
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
      out.angle[j] = static_cast<float>(b.angle - back);
    }
    if (!out.asleep.empty()) out.asleep[j] = world.asleep(e) ? 1 : 0;
    if (const std::optional<SpringDamper> s = world.get<SpringDamper>(e)) {
      out.springs.push_back({static_cast<float>(s->anchor.x), static_cast<float>(s->anchor.y),
                             static_cast<std::uint32_t>(j)});
    }
  }
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
  out.tick = world.tick();
  out.dt = world.settings().dt;
  out.alpha = alpha;
}

}  // namespace fixstep
