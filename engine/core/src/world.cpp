// World: its construction, copies and snapshots, and the members that forward to the kernel
// inside (world_state.hpp); the handle API is in world_handles.cpp, the queries in
// world_queries.cpp.
#include "fixstep/core/world.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "fixstep/core/components.hpp"
#include "fixstep/core/defined_bodies.hpp"
#include "fixstep/core/definition_checks.hpp"
#include "fixstep/core/fnv1a.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/random.hpp"
#include "fixstep/core/segment.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "world_state.hpp"

namespace fixstep {

namespace {
detail::AnyKernel make_kernel(Precision p, const WorldSettings& s) {
  if (p == Precision::f32) return detail::WorldKernel<float>(s);
  return detail::WorldKernel<double>(s);
}

/// A deep copy of *from into `to` (empty when from is): into the state `to` holds when it holds
/// one, so the kernel's copy-assignment keeps the vectors' storage.
template <class T>
void copy_into(std::unique_ptr<T>& to, const std::unique_ptr<T>& from) {
  if (!from) {
    to.reset();
  } else if (to) {
    *to = *from;
  } else {
    to = std::make_unique<T>(*from);
  }
}
}  // namespace

World::World(const World& other) {
  copy_into(state_, other.state_);
}
World& World::operator=(const World& other) {
  if (this != &other) copy_into(state_, other.state_);
  return *this;
}
World::World(World&& other) noexcept = default;
World& World::operator=(World&& other) noexcept = default;
World::~World() = default;

Precision World::precision() const {
  return state_->kernel.index() == 0 ? Precision::f32 : Precision::f64;
}
std::span<const Entity> World::defined_bodies() const {
  return state_->defined;
}
Random& World::random() {
  return state_->random;
}
const Random& World::random() const {
  return state_->random;
}

template <class C>
void World::set(Entity e, const C& component) {
  visit([&](auto& w) { w.set(e, component); });
  if constexpr (std::is_same_v<C, Collider>) queries_changed();
}
template <class C>
void World::remove(Entity e) {
  visit([&](auto& w) { w.template remove<C>(e); });
  if constexpr (std::is_same_v<C, Collider>) queries_changed();
}
template <class C>
std::optional<C> World::get(Entity e) const {
  return visit([&](const auto& w) -> std::optional<C> {
    if (!w.contains(e)) return std::nullopt;
    const C* c = w.template get<C>(e);
    return c ? std::optional<C>(*c) : std::nullopt;
  });
}
// The components (components.hpp): set, remove and get of each, compiled here once.
#define FIXSTEP_WORLD_COMPONENT(C)               \
  template void World::set<C>(Entity, const C&); \
  template void World::remove<C>(Entity);        \
  template std::optional<C> World::get<C>(Entity) const;
FIXSTEP_WORLD_COMPONENT(SpringDamper)
FIXSTEP_WORLD_COMPONENT(ConstantForce)
FIXSTEP_WORLD_COMPONENT(Gravity)
FIXSTEP_WORLD_COMPONENT(LinearDrag)
FIXSTEP_WORLD_COMPONENT(Appearance)
FIXSTEP_WORLD_COMPONENT(Collider)
#undef FIXSTEP_WORLD_COMPONENT

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
                                bool closed, Entity body, bool one_way) {
  std::vector<SegmentDef> chain = polyline_segments(points, restitution, friction, closed);
  const std::size_t first = segments().size();
  for (SegmentDef& s : chain) s.body = body, s.one_way = one_way, add_segment(s);
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
void World::set_pre_solve(PreSolveFn fn, void* context) {
  state_->pre_solve = fn, state_->pre_solve_context = fn ? context : nullptr;
}

void World::step(const TickInput& input) {
  visit([&](auto& w) {
    w.set_pre_solve(state_->pre_solve, state_->pre_solve_context);
    w.step(input);
  });
  queries_changed();
}
void World::step() {
  static const TickInput none{};  // made once: a tick without input costs no TickInput
  step(none);
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
  const Random& random = state_->random;
  if (random.draws() == 0) return bodies;
  std::uint64_t hash = bodies;
  for (int shift = 0; shift < 64; shift += 8) {
    hash = fnv1a_byte(hash, static_cast<unsigned char>(random.state() >> shift));
  }
  return hash;
}
std::size_t World::snapshot_bytes() const {
  // The kernel's arrays, and the block a WorldSnapshot holds them in.
  return sizeof(detail::SnapshotState) + visit([](const auto& w) { return w.snapshot_bytes(); });
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

WorldSnapshot::WorldSnapshot() = default;
WorldSnapshot::WorldSnapshot(const WorldSnapshot& other) {
  copy_into(state_, other.state_);
}
WorldSnapshot& WorldSnapshot::operator=(const WorldSnapshot& other) {
  if (this != &other) copy_into(state_, other.state_);
  return *this;
}
WorldSnapshot::WorldSnapshot(WorldSnapshot&& other) noexcept = default;
WorldSnapshot& WorldSnapshot::operator=(WorldSnapshot&& other) noexcept = default;
WorldSnapshot::~WorldSnapshot() = default;

std::uint64_t WorldSnapshot::tick() const {
  if (!state_) return 0;
  return std::visit([](const auto& w) { return w.tick(); }, state_->kernel);
}

void World::save(WorldSnapshot& out) const {
  if (!out.state_) {
    out.state_ = std::make_unique<detail::SnapshotState>(
        detail::SnapshotState{.kernel = state_->kernel, .random = state_->random});
    return;
  }
  // The kernel's copy-assignment keeps the vectors' storage when the precision matches.
  out.state_->kernel = state_->kernel;
  out.state_->random = state_->random;
}

void World::restore(const WorldSnapshot& snapshot) {
  if (!snapshot.state_) {
    throw std::invalid_argument("snapshot: empty (nothing was saved into it)");
  }
  state_->kernel = snapshot.state_->kernel;
  state_->random = snapshot.state_->random;
  queries_changed();
}

World::World(const WorldDef& def)
    : state_(std::make_unique<detail::WorldState>(detail::WorldState{
          .kernel = make_kernel(def.precision, def.settings),  // validates the settings
          .defined = {},
          .defined_joints = {},
          .random = def.settings.seeding == Seeding::pcg32_srandom
                        ? Random::pcg32(def.settings.seed, 0)
                        : Random(def.settings.seed),
          .warnings = {},
          .queries = {}})) {
  check_limits(def);  // before anything is allocated for the bodies and links
  build(def);         // validates every body, link, plane and segment, naming it
  check_overlaps(def);
  state_->warnings = check_stability(def);
}

std::span<const StabilityFinding> World::warnings() const {
  return state_->warnings;
}

void World::build(const WorldDef& def) {
  std::vector<Entity>& defined = state_->defined;
  defined.reserve(def.bodies.size());
  for (const BodyDef& body : def.bodies) defined.push_back(create_body(body));
  // By place first, so a handle from another definition or world is named as such.
  for (const fixstep::IndexLink& l : fixstep::index_links(def.links, def.bodies.size())) {
    create_link(LinkDef{defined[l.body_a], defined[l.body_b], l.spring});
  }
  for (const PlaneDef& p : def.planes) add_plane(p);
  for (std::size_t i = 0; i < def.segments.size(); ++i) {
    SegmentDef s = def.segments[i];
    if (!s.body.is_null()) {  // the definition's handle: the body made from it here
      const std::optional<std::size_t> at = fixstep::defined_index(s.body, def.bodies.size());
      if (!at) {
        throw std::invalid_argument(fmt::format(
            "segment[{}]: body {}:{} is not one of the definition's {} bodies (use the handles "
            "WorldDef::add_body returns)",
            i, s.body.index1, s.body.generation, def.bodies.size()));
      }
      s.body = defined[*at];
    }
    add_segment(s);
  }
  build_joints(def);  // world_joint_handles.cpp
}

void WorldDef::add_polyline(std::span<const Vec2> points, double restitution, double friction,
                            bool closed, Entity body, bool one_way) {
  std::vector<SegmentDef> chain = polyline_segments(points, restitution, friction, closed);
  for (SegmentDef& s : chain) s.body = body, s.one_way = one_way;
  segments.insert(segments.end(), chain.begin(), chain.end());
}

Entity WorldDef::add_body(BodyDef body) {
  bodies.push_back(std::move(body));
  return fixstep::defined_entity(bodies.size() - 1);
}

Entity WorldDef::find_body(std::string_view name) const {
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (bodies[i].name == name) return fixstep::defined_entity(i);
  }
  return null_entity;
}

Joint WorldDef::find_joint(std::string_view name) const {
  for (std::size_t i = 0; i < joints.size(); ++i) {
    if (joints[i].name == name) return Joint{static_cast<std::uint32_t>(i + 1), 1};
  }
  return Joint{};
}

double energy_balance(const World& sim, double initial_energy) {
  const double residual =
      sim.energy().total() + sim.dissipated_energy() - sim.external_work() - initial_energy;
  return initial_energy != 0.0 ? residual / std::abs(initial_energy) : residual;
}

}  // namespace fixstep
