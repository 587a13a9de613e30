#include "fixstep/core/world.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "fixstep/core/detail/defined_entity.hpp"
#include "fixstep/core/fnv1a.hpp"

namespace fixstep {

namespace {
std::variant<detail::WorldKernel<float>, detail::WorldKernel<double>> make_world(
    Precision p, const WorldSettings& s) {
  if (p == Precision::f32) return detail::WorldKernel<float>(s);
  return detail::WorldKernel<double>(s);
}
}  // namespace

World::World(Precision precision, const WorldSettings& settings)
    : world_(make_world(precision, settings)), random_(settings.seed) {}

Entity World::create_body(const BodyDef& def) {
  const Entity e = visit([&](auto& w) { return w.create_body(def); });
  queries_changed();
  return e;
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
  queries_changed();
  return visit([&](auto& w) { return w.add_plane(def); });
}
std::span<const PlaneDef> World::planes() const {
  return visit([](const auto& w) { return w.planes(); });
}
std::size_t World::add_segment(const SegmentDef& def) {
  queries_changed();
  return visit([&](auto& w) { return w.add_segment(def); });
}
std::size_t World::add_polyline(std::span<const Vec2> points, double restitution, double friction,
                                bool closed, Entity body) {
  std::vector<SegmentDef> chain = polyline_segments(points, restitution, friction, closed);
  const std::size_t first = segments().size();
  for (SegmentDef& s : chain) s.body = body, add_segment(s);
  return first;
}
std::span<const SegmentDef> World::segments() const {
  return visit([](const auto& w) { return w.segments(); });
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
const StepProfile& World::profile() const {
  return visit([](const auto& w) -> const StepProfile& { return w.profile(); });
}
std::span<const Impact> World::impacts() const {
  return visit([](const auto& w) { return w.impacts(); });
}
void World::step(const TickInput& input) {
  visit([&](auto& w) { w.step(input); });
  queries_changed();
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
EnergyReport World::energy() const {
  return visit([](const auto& w) { return w.energy(); });
}
std::uint64_t World::state_hash() const {
  const std::uint64_t bodies = visit([](const auto& w) { return w.state_hash(); });
  if (random_.draws() == 0) return bodies;
  std::uint64_t hash = bodies;
  for (int shift = 0; shift < 64; shift += 8) {
    hash = fnv1a_byte(hash, static_cast<unsigned char>(random_.state() >> shift));
  }
  return hash;
}
std::size_t World::snapshot_bytes() const {
  return visit([](const auto& w) { return w.snapshot_bytes(); });
}

void World::interpolate_positions(double alpha, std::span<float> x, std::span<float> y) const {
  visit([&](const auto& w) {
    const std::size_t n = w.body_count();
    if (x.size() != n || y.size() != n) {
      throw std::invalid_argument(
          fmt::format("interpolate_positions: x and y must hold {} values, not {} and {}", n,
                      x.size(), y.size()));
    }
    for (std::size_t j = 0; j < n; ++j) {
      const double px = w.previous_x()[j], py = w.previous_y()[j];
      x[j] = static_cast<float>(px + (double(w.x()[j]) - px) * alpha);
      y[j] = static_cast<float>(py + (double(w.y()[j]) - py) * alpha);
    }
  });
}

void World::link_ends(std::span<std::uint32_t> a, std::span<std::uint32_t> b) const {
  visit([&](const auto& w) {
    const std::size_t n = w.link_count();
    if (a.size() != n || b.size() != n) {
      throw std::invalid_argument(fmt::format(
          "link_ends: a and b must hold {} values, not {} and {}", n, a.size(), b.size()));
    }
    for (std::size_t i = 0; i < n; ++i) {
      const auto [ia, ib] = w.link_bodies(i);
      a[i] = static_cast<std::uint32_t>(ia);
      b[i] = static_cast<std::uint32_t>(ib);
    }
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
  out.random_ = random_;
}

void World::restore(const WorldSnapshot& snapshot) {
  if (!snapshot.world_) throw std::invalid_argument("snapshot: empty (nothing was saved into it)");
  world_ = *snapshot.world_;
  random_ = snapshot.random_;
  queries_changed();
}

World::World(const WorldDef& def) : World(def.precision, def.settings) {
  defined_.reserve(def.bodies.size());
  for (const BodyDef& body : def.bodies) defined_.push_back(create_body(body));
  // By place first, so a handle from another definition or world is named as such.
  for (const detail::IndexLink& l : detail::index_links(def.links, def.bodies.size())) {
    create_link(LinkDef{defined_[l.body_a], defined_[l.body_b], l.spring});
  }
  for (const PlaneDef& p : def.planes) add_plane(p);
  for (std::size_t i = 0; i < def.segments.size(); ++i) {
    SegmentDef s = def.segments[i];
    if (!s.body.is_null()) {  // the definition's handle: the body made from it here
      const std::optional<std::size_t> at = detail::defined_index(s.body, def.bodies.size());
      if (!at) {
        throw std::invalid_argument(fmt::format(
            "segment[{}]: body {}:{} is not one of the definition's {} bodies (use the handles "
            "WorldDef::add_body returns)",
            i, s.body.index1, s.body.generation, def.bodies.size()));
      }
      s.body = defined_[*at];
    }
    add_segment(s);
  }
}

void WorldDef::add_polyline(std::span<const Vec2> points, double restitution, double friction,
                            bool closed, Entity body) {
  std::vector<SegmentDef> chain = polyline_segments(points, restitution, friction, closed);
  for (SegmentDef& s : chain) s.body = body;
  segments.insert(segments.end(), chain.begin(), chain.end());
}

Entity WorldDef::add_body(BodyDef body) {
  bodies.push_back(std::move(body));
  return detail::defined_entity(bodies.size() - 1);
}

double energy_balance(const World& sim, double initial_energy) {
  const double residual =
      sim.energy().total() + sim.dissipated_energy() - sim.external_work() - initial_energy;
  return initial_energy != 0.0 ? residual / std::abs(initial_energy) : residual;
}

}  // namespace fixstep
