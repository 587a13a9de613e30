// A RenderFrame taken from a World (frame_data.hpp).
#include "fixstep/frame_data.hpp"

#include <optional>

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
  out.springs.clear();
  for (std::size_t j = 0; j < n; ++j) {
    const Entity e = bodies[j];
    if (const std::optional<Appearance> a = world.get<Appearance>(e)) {
      out.radius[j] = static_cast<float>(a->radius);
      out.color[j] = a->color;
    } else {
      out.radius[j] = 0.0f;
      out.color[j] = Rgba8{0, 0, 0, 0};
    }
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
}

}  // namespace fixstep
