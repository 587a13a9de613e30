#include "exact_reference.hpp"

#include <algorithm>
#include <cmath>
#include <fixstep/exact.hpp>

namespace fixstep::cli {

ExactReference::ExactReference(const Scene& scene) : scene_(scene) {
  const bool bounces = std::any_of(scene.bodies.begin(), scene.bodies.end(),
                                   [&](const BodyDef& b) { return bouncing(b); });
  if (!scene.links.empty() && !bounces) {
    network_ = exact::LinearNetwork::make(scene.bodies, scene.links);
  }
}

void ExactReference::at(double t, std::vector<std::optional<Body>>& out) const {
  out.assign(scene_.bodies.size(), std::nullopt);
  if (network_) {
    states_.resize(scene_.bodies.size());
    network_->state(t, states_);
    for (std::size_t j = 0; j < states_.size(); ++j) out[j] = states_[j];
  } else if (scene_.links.empty()) {
    for (std::size_t j = 0; j < out.size(); ++j) {
      if (!bouncing(scene_.bodies[j])) out[j] = exact::solve(scene_.bodies[j], t);
    }
  }
}

bool ExactReference::bouncing(const BodyDef& b) const {
  return b.collider && !scene_.planes.empty();
}

std::optional<double> exact_error(const ExactReference& reference, const Simulation& sim) {
  std::vector<std::optional<Body>> exact;
  reference.at(sim.time(), exact);
  std::optional<double> worst;
  for (std::size_t j = 0; j < sim.body_count(); ++j) {
    if (exact[j]) {
      const Body b = sim.body_at(j);
      const double e =
          std::hypot(b.position.x - exact[j]->position.x, b.position.y - exact[j]->position.y);
      worst = std::max(worst.value_or(0.0), e);
    }
  }
  return worst;
}

}  // namespace fixstep::cli
