#include "fixstep/core/stability.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <map>
#include <mutex>
#include <stdexcept>
#include <tuple>

#include "fixstep/core/components.hpp"
#include "fixstep/core/defined_bodies.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/shape.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/world_settings.hpp"
#include "stability_internal.hpp"
#include "stability_verdict.hpp"
#include "world_kernel.hpp"

namespace fixstep {

double amplification(Integrator integrator, double omega, double gamma, double h) {
  if (const double c = detail::unit_scale(omega, gamma); c != 1.0) {  // within a world's ranges
    return amplification(integrator, omega / c, gamma / c, h * c);
  }
  detail::WorldKernel<double> w(
      WorldSettings{.dt = h, .integrator = integrator, .substeps = 1, .flush_denormals = false});
  auto unit = [&](Vec2 position, Vec2 velocity) {
    BodyDef d;
    d.body = Body{.mass = 1.0, .position = position, .velocity = velocity};
    if (omega > 0.0) {
      d.spring = SpringDamper{.anchor = {}, .stiffness = omega * omega, .damping = gamma};
    } else if (gamma > 0.0) {
      d.drag = LinearDrag{gamma};
    }
    w.create_body(d);
  };
  unit({1.0, 0.0}, {});  // first column of M: the step applied to (x, v) = (1, 0)
  unit({}, {1.0, 0.0});  // second column: (0, 1)
  w.step();
  return detail::spectral_radius(w.x()[0], w.x()[1], w.vx()[0], w.vx()[1]);
}

double max_stable_step(Integrator integrator, double omega, double gamma) {
  if (omega == 0.0 && gamma == 0.0) return std::numeric_limits<double>::infinity();
  static std::mutex mutex;
  static std::map<std::tuple<Integrator, double, double>, double> cache;
  const std::lock_guard lock(mutex);
  const auto key = std::make_tuple(integrator, omega, gamma);
  if (auto it = cache.find(key); it != cache.end()) return it->second;

  // The dimensionless step s = rate·h (rate = ω, or γ without spring).
  const double rate = omega > 0.0 ? omega : gamma;
  const double result = detail::largest_stable_step(rate, [&](double s) {
    // A rate so small that s / rate overflows (γ = 1e-310 1/s: a subnormal drag, or a drag
    // over a huge mass) puts the bound beyond every double: each step is stable. (Before,
    // World refused the infinite step and the scene got "dt must be finite (got inf)".)
    const double h = s / rate;
    return !std::isfinite(h) ||
           amplification(integrator, omega, gamma, h) <= 1.0 + detail::stability_tolerance;
  });
  cache.emplace(key, result);
  return result;
}

namespace {

/// The finding for a body whose k/m or (b + c)/m overflows a double: no step of any
/// integrator can follow it.
void judge_out_of_range(const BodyDef& def, BodyStability& r) {
  const double m = def.body.mass;
  r.verdict = Stability::unstable;
  r.radius = std::numeric_limits<double>::infinity();
  r.message = fmt::format(
      "body '{}' has k/m = {:g} 1/s² and (damping + drag)/m = {:g} 1/s (mass {:g} kg): "
      "beyond the range of a double, so no integrator and no step can follow it",
      def.name, (def.spring ? def.spring->stiffness : 0.0) / m, r.gamma, m);
}

/// check_stability for one dynamic body with a spring or damping (its ω and γ already in r).
void judge_body(const BodyDef& def, Integrator integrator, double dt, int substeps,
                BodyStability& r) {
  r.h = dt / substeps;
  if (!std::isfinite(r.omega * r.omega) || !std::isfinite(r.gamma)) {
    judge_out_of_range(def, r);
    return;
  }
  r.max_step = max_stable_step(integrator, r.omega, r.gamma);
  r.radius = amplification(integrator, r.omega, r.gamma, r.h);
  const bool spring = r.omega > 0.0;
  detail::GuardFinding f =
      detail::finding_of(fmt::format("body '{}'", def.name), integrator, dt, substeps, r);
  f.step_name = spring ? "ω·h" : "γ·h";
  f.rate = spring ? r.omega : r.gamma;
  f.named_max_step = r.max_step;
  f.rates = {{{"ω", r.omega, "rad/s"}, {"γ", r.gamma, "1/s"}, {}}};
  detail::Judgement j = detail::judge(f, [&](double h) {
    return amplification(integrator, r.omega, r.gamma, h) > 1.0 + detail::stability_tolerance;
  });
  r.verdict = j.verdict, r.min_substeps = j.min_substeps, r.message = std::move(j.message);
}

}  // namespace

std::vector<BodyStability> check_stability(std::span<const BodyDef> bodies, Integrator integrator,
                                           double dt, int substeps) {
  std::vector<BodyStability> out;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const BodyDef& def = bodies[i];
    if (def.type != BodyType::dynamic) continue;  // not integrated: nothing to judge
    BodyStability r;
    r.body = fixstep::defined_entity(i);
    const double m = def.body.mass;
    r.omega = def.spring ? std::sqrt(def.spring->stiffness / m) : 0.0;
    r.gamma =
        ((def.spring ? def.spring->damping : 0.0) + (def.drag ? def.drag->coefficient : 0.0)) / m;
    if (r.omega == 0.0 && r.gamma == 0.0) continue;
    judge_body(def, integrator, dt, substeps, r);
    out.push_back(std::move(r));
  }
  return out;
}

}  // namespace fixstep

namespace fixstep {

std::vector<bool> detail::linked_by_index(std::size_t body_count,
                                          std::span<const fixstep::IndexLink> links) {
  std::vector<bool> linked(body_count, false);
  for (const fixstep::IndexLink& link : links) linked[link.body_a] = linked[link.body_b] = true;
  return linked;
}

std::vector<bool> linked_bodies(std::size_t body_count, std::span<const LinkDef> links) {
  std::vector<bool> linked(body_count, false);
  for (std::size_t l = 0; l < links.size(); ++l) {  // flags from each end's place: no copy
    const auto a = fixstep::defined_index(links[l].body_a, body_count);
    const auto b = fixstep::defined_index(links[l].body_b, body_count);
    if (!a || !b) {  // index_links names the link and its bad end
      (void)fixstep::index_links(links.first(l + 1), body_count);
    }
    linked[*a] = linked[*b] = true;
  }
  return linked;
}

std::optional<NetworkStability> check_linked_stability(std::span<const BodyDef> all_bodies,
                                                       std::span<const LinkDef> all_links,
                                                       Integrator integrator, double dt,
                                                       int substeps) {
  if (all_links.empty()) return std::nullopt;
  std::vector<fixstep::IndexLink> links = fixstep::index_links(all_links, all_bodies.size());
  const std::vector<bool> linked = detail::linked_by_index(all_bodies.size(), links);
  std::vector<std::size_t> index(all_bodies.size()), order;
  std::vector<BodyDef> bodies;
  for (std::size_t i = 0; i < all_bodies.size(); ++i) {
    if (!linked[i]) continue;
    index[i] = bodies.size();
    order.push_back(i);
    bodies.push_back(all_bodies[i]);
  }
  for (fixstep::IndexLink& l : links) l.body_a = index[l.body_a], l.body_b = index[l.body_b];
  NetworkStability r = detail::network_stability(bodies, links, integrator, dt, substeps);
  r.fastest_body = fixstep::defined_entity(order[r.fastest_body.slot()]);
  return r;
}

namespace {
/// "body[I]" for the definition's body I, else "body S:G" (its handle's slot and generation).
std::string body_label(Entity e, std::size_t defined) {
  if (const auto i = fixstep::defined_index(e, defined)) return fmt::format("body[{}]", *i);
  return fmt::format("body {}:{}", e.index1, e.generation);
}

/// explain_fault of a contact cap (StateFault::cap set).
std::string explain_cap(const WorldSettings& settings, const StateFault& f, std::size_t defined) {
  const std::string head =
      fmt::format("{} \"{}\": contacts at tick {} (t = {:g} s): {} = {:.0f} reached",
                  body_label(f.body, defined), f.name, f.tick, f.time, f.cap, f.value);
  if (f.cap == "max_candidate_pairs") {
    return fmt::format(
        "{}: the broadphase found more candidate pairs among {}, so the tick's contacts were "
        "not resolved. Likely cause: bodies overlapping one another in a crowd, or discs moving "
        "many radii per tick through a crowd of discs (the tick's windows did not part them): "
        "fewer or smaller bodies, a smaller dt (now {:g} s), slower bodies",
        head, f.with, settings.dt);
  }
  if (f.cap == "max_vetoed_pairs") {
    return fmt::format(
        "{}: the broadphase dropped more pairs that can never touch (a collision filter's, a "
        "joint's, two shapes of one body, two sleepers) among {}, so the tick's contacts were "
        "not resolved. Likely cause: a crowd of bodies kept apart at one place: fewer of them, "
        "or spread out",
        head, f.with);
  }
  return fmt::format(
      "{}: its impact with {} was not resolved. Likely cause: fast bodies driven into one "
      "another (a row of discs into a peg) or a body bouncing between close planes, each impact "
      "predicting again: a smaller dt (now {:g} s), slower bodies or fewer in a row",
      head, f.with, settings.dt);
}

/// The likely cause of a kinematic body leaving the range: it moves at its velocity, which
/// nothing but input changes.
std::string explain_kinematic(const std::string& head, const BodyDef& d) {
  return fmt::format(
      "{}. Likely cause: the body is kinematic: it moves at the velocity it is given ({:g}, {:g} "
      "m/s at creation) and only input changes that: check it, and any velocity input gives the "
      "body (TickInput, a script's or recording's body velocity)",
      head, d.body.velocity.x, d.body.velocity.y);
}

/// The unit of a StateFault field.
const char* field_unit(const std::string& field) {
  if (field == "x" || field == "y") return "m";
  if (field == "angle") return "rad";
  if (field == "angular_velocity") return "rad/s";
  if (field == "dissipated") return "J";
  return "m/s";
}

/// The likely cause of a disc's turn or its energy account leaving the range.
std::string explain_account(const std::string& head, const BodyDef& d, const std::string& field) {
  if (field == "dissipated") {
    return fmt::format(
        "{}. Likely cause: damping, drag or contacts took more energy than a number holds: the "
        "body's mass ({:g} kg) and speed, or its damping and drag coefficients, are extreme",
        head, d.body.mass);
  }
  if (!d.shapes.empty()) {
    const double inertia = d.inertia ? *d.inertia : body_mass(d.shapes, d.body.mass).inertia;
    return fmt::format(
        "{}. Likely cause: a torque or angular impulse input, or a contact, turned the body by "
        "1 / I per unit of angular impulse: its moment of inertia {:g} kg*m^2 (from its shapes, "
        "or BodyDef::inertia), or its starting angular velocity ({:g} rad/s); check them",
        head, inertia, d.body.angular_velocity);
  }
  const double r = d.collider ? d.collider->radius : 0.0;
  const double inertia =
      d.collider && d.collider->inertia ? *d.collider->inertia : 0.5 * d.body.mass * r * r;
  return fmt::format(
      "{}. Likely cause: friction turns the disc by r / I per unit impulse: its moment of inertia "
      "{:g} kg*m^2 against m r^2 = {:g} kg*m^2 (mass {:g} kg, radius {:g} m), or its starting "
      "angular velocity ({:g} rad/s); check them",
      head, inertia, d.body.mass * r * r, d.body.mass, r, d.body.angular_velocity);
}

}  // namespace

std::string explain_fault(std::span<const BodyDef> bodies, std::span<const LinkDef> links,
                          const WorldSettings& settings, const StateFault& f) {
  if (!f.cap.empty()) return explain_cap(settings, f, bodies.size());
  const std::string head = fmt::format(
      "{} \"{}\": state left the finite range at tick {} (t = {:g} s): {} = {:g} {} ({})",
      body_label(f.body, bodies.size()), f.name, f.tick, f.time, f.field, f.value,
      field_unit(f.field),
      f.field == "dissipated" ? std::string("the energy account must stay finite")
                              : fmt::format("allowed |value| <= {:g}", max_state_magnitude));
  const std::optional<std::size_t> defined = fixstep::defined_index(f.body, bodies.size());
  if (!defined) return head + ".";
  const std::size_t i = *defined;
  if (f.field == "angle" || f.field == "angular_velocity" || f.field == "dissipated") {
    return explain_account(head, bodies[i], f.field);
  }
  if (bodies[i].type == BodyType::kinematic) return explain_kinematic(head, bodies[i]);
  if (bodies[i].type == BodyType::static_body) {
    return head +
           ". Likely cause: the body is static and never moves: its position is beyond "
           "the range; place it within it";
  }
  const std::string_view method = integrator_name(settings.integrator);
  const double dt = settings.dt;
  const int substeps = settings.substeps;
  if (linked_bodies(bodies.size(), links)[i]) {
    const NetworkStability net =
        *check_linked_stability(bodies, links, settings.integrator, dt, substeps);
    if (net.verdict == Stability::unstable) {
      return fmt::format("{}. Likely cause: {}{}", head, net.message,
                         detail::stable_from(net.min_substeps, net.max_step, substeps));
    }
    return fmt::format(
        "{}. Likely cause: the body is in a network of {} bodies and {} spring{} within {}'s "
        "stability bound at h = {:g} s (ω_max·h = {:.4g}, largest stable step {:g} s), so the "
        "motion itself grew: check the forces (gravity, constant forces, pushes), rest-length "
        "springs stretched far from their starting lengths, and the starting values",
        head, net.bodies, net.springs, net.springs == 1 ? "" : "s", method, net.h,
        net.omega_max * net.h, net.max_step);
  }
  const std::vector<BodyStability> own =
      check_stability(bodies.subspan(i, 1), settings.integrator, dt, substeps);
  if (!own.empty() && own.front().verdict == Stability::unstable) {
    const BodyStability& r = own.front();
    return fmt::format("{}. Likely cause: {}{}", head, r.message,
                       detail::stable_from(r.min_substeps, r.max_step, substeps));
  }
  const BodyDef& d = bodies[i];
  return fmt::format(
      "{}. Likely cause: the body's spring and damping are within {}'s stability bound at h = "
      "{:g} s, so the motion itself grew: check its forces ({}) and its starting values",
      head, method, dt / substeps,
      d.gravity || d.constant_force ? "gravity or a constant force accelerates it for the whole run"
                                    : "a push, or extreme mass, stiffness or velocity");
}

}  // namespace fixstep
