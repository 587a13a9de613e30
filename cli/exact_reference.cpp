#include "exact_reference.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fixstep/core/components.hpp>
#include <fixstep/core/defined_bodies.hpp>
#include <fixstep/core/exact.hpp>
#include <fixstep/core/step_results.hpp>
#include <numeric>

namespace fixstep::cli {

TouchedBodies::TouchedBodies(const Scene& scene)
    : since_(scene.def.bodies.size(), 0),
      component_(scene.def.bodies.size()),
      next_(scene.def.bodies.size()),
      dynamic_(scene.def.bodies.size()) {
  // The links' connected components (union-find with path halving), each kept as a ring.
  std::iota(component_.begin(), component_.end(), std::size_t{0});
  auto root = [&](std::size_t j) {
    while (component_[j] != j) j = component_[j] = component_[component_[j]];
    return j;
  };
  std::iota(next_.begin(), next_.end(), std::size_t{0});
  for (const fixstep::IndexLink& l :
       fixstep::index_links(scene.def.links, scene.def.bodies.size())) {
    const std::size_t a = root(l.body_a), b = root(l.body_b);
    if (a == b) continue;
    component_[b] = a;
    std::swap(next_[l.body_a], next_[l.body_b]);  // splices the two rings into one
  }
  for (std::size_t j = 0; j < scene.def.bodies.size(); ++j) {
    dynamic_[j] = scene.def.bodies[j].type == BodyType::dynamic ? 1 : 0;
    dynamic_count_ += dynamic_[j];
  }
}

void TouchedBodies::clear() {
  std::fill(since_.begin(), since_.end(), 0);
  first_ = 0;
  count_ = 0;
}

void TouchedBodies::touch(std::size_t j, std::uint64_t tick) {
  if (j >= since_.size() || since_[j] != 0 || !dynamic_[j]) return;
  std::size_t k = j;
  do {  // every body of j's link component: the links pass the contact on
    if (since_[k] == 0 && dynamic_[k]) {
      since_[k] = tick;
      ++count_;
    }
    k = next_[k];
  } while (k != j);
  if (first_ == 0) first_ = tick;
}

void TouchedBodies::after_tick(const World& sim) {
  if (count_ == dynamic_count_) return;
  const std::uint64_t tick = sim.tick();
  for (const Impact& i : sim.impacts())
    touch(sim.index_of(i.a), tick), touch(sim.index_of(i.b), tick);
  for (const ContactEvent& c : sim.contacts_begun()) {
    touch(sim.index_of(c.a), tick);
    touch(sim.index_of(c.b), tick);
  }
}

std::string touched_clause(const TouchedBodies& touched, std::size_t bodies) {
  if (!touched.first()) return {};
  return fmt::format("{} touched {} of {} bodies from tick {} on",
                     touched.count() == 1 ? "a disc contact" : "disc contacts", touched.count(),
                     bodies, *touched.first());
}

namespace {

/// Bodies at either end of some link of `def`.
std::size_t linked_bodies(const WorldDef& def) {
  std::vector<char> linked(def.bodies.size(), 0);
  std::size_t n = 0;
  for (const LinkDef& l : def.links) {
    for (const Entity e : {l.body_a, l.body_b}) {
      if (e.slot() < linked.size() && linked[e.slot()] == 0) linked[e.slot()] = 1, ++n;
    }
  }
  return n;
}

}  // namespace

ExactReference::ExactReference(const Scene& scene) : scene_(scene) {
  const bool bounces = std::any_of(scene.def.bodies.begin(), scene.def.bodies.end(),
                                   [&](const BodyDef& b) { return bouncing(b); });
  // The network's solution is a dense eigen-decomposition: O(n^2) memory, O(n^3) time.
  if (!scene.def.links.empty() && !bounces &&
      linked_bodies(scene.def) <= max_exact_network_bodies) {
    network_ = exact::LinearNetwork::make(scene.def.bodies, scene.def.links);
  }
}

void ExactReference::at(double t, std::vector<std::optional<Body>>& out,
                        const TouchedBodies* touched) const {
  out.assign(scene_.def.bodies.size(), std::nullopt);
  if (network_) {
    states_.resize(scene_.def.bodies.size());
    network_->state(t, states_);
    for (std::size_t j = 0; j < states_.size(); ++j) out[j] = states_[j];
  } else if (scene_.def.links.empty()) {
    for (std::size_t j = 0; j < out.size(); ++j) {
      if (!bouncing(scene_.def.bodies[j])) out[j] = exact::solve(scene_.def.bodies[j], t);
    }
  }
  if (touched && touched->first()) {
    for (std::size_t j = 0; j < out.size(); ++j) {
      if (touched->since(j)) out[j].reset();  // the exact solutions know no contacts
    }
  }
}

bool ExactReference::bouncing(const BodyDef& b) const {
  return b.collider && !scene_.def.planes.empty();
}

std::optional<double> exact_error(const ExactReference& reference, const World& sim,
                                  const TouchedBodies* touched) {
  std::vector<std::optional<Body>> exact;
  reference.at(sim.time(), exact, touched);
  std::optional<double> worst;
  for (std::size_t j = 0; j < sim.body_count(); ++j) {
    // A static body never moves: its error is 0 whatever the integrator (nothing to measure).
    if (exact[j] && sim.type(sim.bodies()[j]) != BodyType::static_body) {
      const Body b = sim.body(sim.bodies()[j]);
      const double e =
          std::hypot(b.position.x - exact[j]->position.x, b.position.y - exact[j]->position.y);
      worst = std::max(worst.value_or(0.0), e);
    }
  }
  return worst;
}

}  // namespace fixstep::cli
