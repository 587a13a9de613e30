#include "scene_check.hpp"

#include <cxxabi.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <optional>
#include <stdexcept>
#include <typeinfo>

#include "fixstep/core/components.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_settings.hpp"
#include "fixstep/scene/scene.hpp"
#include "fixstep/scene/scene_stability.hpp"

namespace fixstep::fuzz {
namespace {

std::string type_name(const std::exception& e) {
  int status = 0;
  char* name = abi::__cxa_demangle(typeid(e).name(), nullptr, nullptr, &status);
  std::string out = status == 0 && name ? name : typeid(e).name();
  std::free(name);
  return out;
}

Outcome unexpected(std::string_view where, const std::exception& e) {
  return {Verdict::finding,
          fmt::format("{} threw {} (not fixstep::SceneError): {}", where, type_name(e), e.what())};
}

Outcome unexpected(std::string_view where) {
  return {Verdict::finding, fmt::format("{} threw a non-std::exception", where)};
}

bool finite(const Vec2& v) {
  return std::isfinite(v.x) && std::isfinite(v.y);
}

bool small(double v) {
  return std::abs(v) <= bounded_max;
}
bool small(const Vec2& v) {
  return small(v.x) && small(v.y);
}

/// See bounded_max: a scene whose non-finite states are findings.
bool bounded_scene(const Scene& scene) {
  if (scene.def.allow_unstable) return false;
  const bool links_ok =
      std::all_of(scene.def.links.begin(), scene.def.links.end(), [](const LinkDef& l) {
        return small(l.spring.stiffness) && small(l.spring.damping) && small(l.spring.rest_length);
      });
  if (!links_ok) return false;
  const bool planes_ok = std::all_of(scene.def.planes.begin(), scene.def.planes.end(),
                                     [](const PlaneDef& p) { return small(p.offset); });
  if (!planes_ok) return false;
  return std::all_of(scene.def.bodies.begin(), scene.def.bodies.end(), [](const BodyDef& d) {
    const bool spring_ok = !d.spring || (small(d.spring->anchor) && small(d.spring->stiffness) &&
                                         small(d.spring->damping) && small(d.spring->rest_length));
    return d.body.mass >= bounded_min_mass && small(d.body.mass) && small(d.body.position) &&
           small(d.body.velocity) && spring_ok &&
           (!d.constant_force || small(d.constant_force->force)) &&
           (!d.gravity || small(d.gravity->acceleration)) &&
           (!d.drag || small(d.drag->coefficient)) && (!d.collider || small(d.collider->radius));
  });
}

}  // namespace

Outcome check_scene_text(std::string_view text) {
  Scene scene;
  try {
    scene = parse_scene(text, "fuzz.toml");
  } catch (const SceneError& e) {
    return {Verdict::rejected, e.what()};
  } catch (const std::exception& e) {
    return unexpected("parse_scene", e);
  } catch (...) {
    return unexpected("parse_scene");
  }

  // The work of one tick (see max_body_substeps); beyond the budget, the scene is only loaded.
  const std::uint64_t size = scene.def.bodies.size() + scene.def.links.size();
  const std::uint64_t discs = scene.def.settings.contacts
                                  ? static_cast<std::uint64_t>(std::count_if(
                                        scene.def.bodies.begin(), scene.def.bodies.end(),
                                        [](const BodyDef& d) { return d.collider.has_value(); }))
                                  : 0;
  const bool implicit_network =
      scene.def.settings.integrator == Integrator::implicit_euler && !scene.def.links.empty();
  const std::uint64_t per_tick =
      static_cast<std::uint64_t>(std::max(scene.def.settings.substeps, 1)) *
      std::max<std::uint64_t>(size + disc_weight * discs, 1) *
      (implicit_network ? scene.def.bodies.size() : 1);
  if (size > max_built_size || per_tick > max_body_substeps) return {Verdict::accepted, {}};

  std::optional<World> sim;
  try {
    sim.emplace(World(scene.def));
  } catch (const UnstableDefinition& e) {  // the stability guard: what every program locates
    return {Verdict::rejected, located(scene, e).what()};
  } catch (const SceneError& e) {
    return {Verdict::rejected, e.what()};
  } catch (const std::invalid_argument& e) {
    return {Verdict::rejected_by_world, e.what()};
  } catch (const std::exception& e) {
    return unexpected("make_world", e);
  } catch (...) {
    return unexpected("make_world");
  }

  const int ticks =
      static_cast<int>(std::clamp<std::uint64_t>(max_body_substeps / per_tick, 1, max_ticks));
  try {
    for (int tick = 1; tick <= ticks; ++tick) {
      sim->step();
      for (std::size_t i = 0; i < sim->body_count(); ++i) {
        const Entity e = sim->bodies()[i];
        const Body b = sim->body(e);
        if (!finite(b.position) || !finite(b.velocity)) {
          // Whatever the scene, the runtime guard must have caught it (World::fault), on this
          // tick or before: a NaN or infinity it missed would spread silently.
          const bool caught = sim->fault().has_value() && sim->fault()->tick <= sim->tick();
          return {bounded_scene(scene) || !caught ? Verdict::finding : Verdict::overflowed,
                  fmt::format("non-finite state at tick {} (dt {} s, {}, {}, substeps {}): "
                              "body[{}] \"{}\" position ({}, {}) velocity ({}, {}){}",
                              tick, scene.def.settings.dt,
                              integrator_name(scene.def.settings.integrator),
                              scene.def.precision == Precision::f32 ? "f32" : "f64",
                              scene.def.settings.substeps, i, sim->name(e), b.position.x,
                              b.position.y, b.velocity.x, b.velocity.y,
                              caught ? "" : "; the runtime guard did not report it")};
        }
      }
    }
  } catch (const std::exception& e) {
    return unexpected("World::step", e);
  } catch (...) {
    return unexpected("World::step");
  }
  return {Verdict::accepted, {}};
}

}  // namespace fixstep::fuzz
