#include "fixstep/world.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "fixstep/disc_overlap.hpp"
#include "fixstep/float_mode.hpp"
#include "fixstep/limits.hpp"
#include "fixstep/stability.hpp"

namespace fixstep {

namespace {
std::variant<detail::WorldKernel<float>, detail::WorldKernel<double>> make_world(
    Precision p, const WorldSettings& s) {
  if (p == Precision::f32) return detail::WorldKernel<float>(s);
  return detail::WorldKernel<double>(s);
}
}  // namespace

World::World(Precision precision, const WorldSettings& settings)
    : world_(make_world(precision, settings)) {}

Entity World::create_body(const BodyDef& def) {
  return visit([&](auto& w) { return w.create_body(def); });
}
Link World::create_link(const LinkDef& def) {
  return visit([&](auto& w) { return w.create_link(def); });
}
std::span<const Entity> World::bodies() const {
  return visit([](const auto& w) { return w.entities(); });
}

void World::body_energies(std::span<double> out) const {
  if (out.size() != body_count()) {
    throw std::invalid_argument(
        fmt::format("body_energies: out holds {} values for {} bodies", out.size(), body_count()));
  }
  visit([&](const auto& w) { w.body_energies(out); });
}

unsigned World::active_terms() const {
  return visit([](const auto& w) { return w.active_terms(); });
}

int World::threads_used() const {
  return visit([](const auto& w) { return w.threads_used(); });
}

std::size_t World::link_count() const {
  return visit([](const auto& w) { return w.link_count(); });
}
std::size_t World::add_plane(const PlaneDef& def) {
  return visit([&](auto& w) { return w.add_plane(def); });
}
std::span<const PlaneDef> World::planes() const {
  return visit([](const auto& w) { return w.planes(); });
}
double World::dissipated_energy() const {
  return visit([](const auto& w) { return w.dissipated_energy(); });
}
double World::external_work() const {
  return visit([](const auto& w) { return w.external_work(); });
}
const ContactStats& World::contact_stats() const {
  return visit([](const auto& w) -> const ContactStats& { return w.contact_stats(); });
}
std::span<const Impact> World::impacts() const {
  return visit([](const auto& w) { return w.impacts(); });
}
BodyType World::type_at(std::size_t index) const {
  return visit([&](const auto& w) { return w.type_at(index); });
}
void World::step(const TickInput& input) {
  visit([&](auto& w) { w.step(input); });
}
void World::set_keep_previous(bool keep) {
  visit([&](auto& w) { w.set_keep_previous(keep); });
}
const std::optional<StateFault>& World::fault() const {
  return visit([](const auto& w) -> const std::optional<StateFault>& { return w.fault(); });
}
std::uint64_t World::tick() const {
  return visit([](const auto& w) { return w.tick(); });
}
double World::time() const {
  return visit([](const auto& w) { return w.time(); });
}
const WorldSettings& World::settings() const {
  return visit([](const auto& w) -> const WorldSettings& { return w.settings(); });
}
std::size_t World::body_count() const {
  return visit([](const auto& w) { return w.body_count(); });
}
const std::string& World::name(std::size_t index) const {
  return visit([&](const auto& w) -> const std::string& { return w.name(index); });
}
EnergyReport World::energy() const {
  return visit([](const auto& w) { return w.energy(); });
}
std::uint64_t World::state_hash() const {
  return visit([](const auto& w) { return w.state_hash(); });
}
std::size_t World::snapshot_bytes() const {
  return visit([](const auto& w) { return w.snapshot_bytes(); });
}
Body World::body_at(std::size_t i) const {
  return visit([&](const auto& w) { return w.body(w.entities()[i]); });
}

void World::fill_render_frame(double alpha, RenderFrame& out) const {
  visit([&](const auto& w) {
    const std::size_t n = w.body_count();
    out.x.resize(n);
    out.y.resize(n);
    out.ids.assign(w.entities().begin(), w.entities().end());
    out.radius.resize(n);
    out.color.resize(n);
    out.springs.clear();
    const double a = alpha;
    for (std::size_t j = 0; j < n; ++j) {
      const double px = w.previous_x()[j], py = w.previous_y()[j];
      out.x[j] = static_cast<float>(px + (double(w.x()[j]) - px) * a);
      out.y[j] = static_cast<float>(py + (double(w.y()[j]) - py) * a);
      const Entity e = w.entities()[j];
      if (const Appearance* ap = w.template get<Appearance>(e)) {
        out.radius[j] = static_cast<float>(ap->radius);
        out.color[j] = ap->color;
      } else {
        out.radius[j] = 0.0f;
        out.color[j] = Rgba8{0, 0, 0, 0};
      }
      if (const SpringDamper* s = w.template get<SpringDamper>(e)) {
        out.springs.push_back({static_cast<float>(s->anchor.x), static_cast<float>(s->anchor.y),
                               static_cast<std::uint32_t>(j)});
      }
    }
    out.links.resize(w.link_count());
    for (std::size_t i = 0; i < w.link_count(); ++i) {
      const auto [a, b] = w.link_bodies(i);
      out.links[i] = {static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(b)};
    }
    out.planes.assign(w.planes().begin(), w.planes().end());
  });
}

std::uint64_t WorldSnapshot::tick() const {
  if (!world_) return 0;
  return std::visit([](const auto& w) { return w.tick(); }, *world_);
}

void World::save(WorldSnapshot& out) const {
  if (out.world_ && out.world_->index() == world_.index()) {
    *out.world_ = world_;  // World's copy-assignment: vectors keep their storage
  } else {
    out.world_.emplace(world_);
  }
}

void World::restore(const WorldSnapshot& snapshot) {
  if (!snapshot.world_) throw std::invalid_argument("snapshot: empty (nothing was saved into it)");
  world_ = *snapshot.world_;
}

namespace {
/// Throws std::invalid_argument with the stability guard's first finding of an unstable body or
/// network (unless def.allow_unstable); returns the guard's warnings: near the bound, or unstable
/// and allowed.
std::vector<std::string> judge_stability(const WorldDef& def) {
  const IeeeFloatMode ieee;  // the same verdict whatever the caller's FPU mode
  std::vector<std::string> warnings;
  const WorldSettings& s = def.settings;
  auto refuse = [&](const std::string& message, int min_substeps, double max_step) {
    throw std::invalid_argument(min_substeps > 0
                                    ? fmt::format("{}; stable from substeps = {} (dt <= {:.4g} s)",
                                                  message, min_substeps, max_step * s.substeps)
                                    : message);
  };
  const std::vector<bool> linked = linked_bodies(def.bodies.size(), def.links);
  for (const BodyStability& r : check_stability(def.bodies, s.integrator, s.dt, s.substeps)) {
    if (linked[r.body] || r.verdict == Stability::stable) continue;
    if (r.verdict == Stability::unstable && !def.allow_unstable) {
      refuse(r.message, r.min_substeps, r.max_step);
    }
    warnings.push_back(r.message);
  }
  const auto net = check_linked_stability(def.bodies, def.links, s.integrator, s.dt, s.substeps);
  if (net && net->verdict != Stability::stable) {
    if (net->verdict == Stability::unstable && !def.allow_unstable) {
      refuse(net->message, net->min_substeps, net->max_step);
    }
    warnings.push_back(net->message);
  }
  return warnings;
}
}  // namespace

World::World(const WorldDef& def) : World(def.precision, def.settings) {
  // Built first so invalid settings, bodies and links are reported by World, then judged.
  std::vector<Entity> bodies;
  bodies.reserve(def.bodies.size());
  for (const BodyDef& body : def.bodies) bodies.push_back(create_body(body));
  for (const BodyLink& l : def.links) {
    if (l.body_a >= bodies.size() || l.body_b >= bodies.size()) {
      throw std::invalid_argument(fmt::format("link: body index out of range ({} and {} of {})",
                                              l.body_a, l.body_b, bodies.size()));
    }
    create_link(LinkDef{bodies[l.body_a], bodies[l.body_b], l.spring});
  }
  for (const PlaneDef& p : def.planes) add_plane(p);
  if (const auto pair = first_disc_overlap(def)) {
    const auto name = [&](std::size_t i) {
      return def.bodies[i].name.empty() ? fmt::format("body {}", i)
                                        : fmt::format("body '{}'", def.bodies[i].name);
    };
    throw std::invalid_argument(fmt::format(
        "{} and {} overlap by {:g} m at tick 0 (discs of a world with contacts must start "
        "apart or touching)",
        name(pair->first), name(pair->second),
        disc_overlap_depth(def.bodies[pair->first], def.bodies[pair->second])));
  }
  check_world_limits(def.bodies, def.links, def.planes,
                     def.settings);  // before the guard's power iteration
  if (!def.stability_checked) {
    for (std::string& w : judge_stability(def)) add_warning(std::move(w));
  }
}

double energy_balance(const World& sim, double initial_energy) {
  const double residual =
      sim.energy().total() + sim.dissipated_energy() - sim.external_work() - initial_energy;
  return initial_energy != 0.0 ? residual / std::abs(initial_energy) : residual;
}

}  // namespace fixstep
