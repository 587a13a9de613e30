// The exact solution a scene's run is measured against, shared by `run` (exact_error=) and
// `compare` (each tile's error), so both print the same digits for the same state.
#pragma once

#include <fixstep/exact.hpp>
#include <fixstep/scene.hpp>
#include <fixstep/simulation.hpp>
#include <optional>
#include <vector>

namespace fixstep::cli {

/// The exact solution of a scene where one exists: per body (exact::solve) when the scene has
/// no links, for the whole network (exact::LinearNetwork) when it has and they are linear
/// with proportional damping. Bodies that bounce on the scene's planes have none (the exact
/// solutions know no contacts), nor has a network holding one. Holds a reference to `scene`,
/// which must outlive it.
class ExactReference {
 public:
  explicit ExactReference(const Scene& scene);
  /// Fills out[j] with body j's exact state at t (s), or nullopt where there is none.
  void at(double t, std::vector<std::optional<Body>>& out) const;

 private:
  [[nodiscard]] bool bouncing(const BodyDef& b) const;

  const Scene& scene_;
  std::optional<exact::LinearNetwork> network_;
  mutable std::vector<Body> states_;
};

/// Largest position error (m) over the bodies, |x - x_exact| at sim.time(), against the exact
/// solution of the bodies that have one; nullopt when none has (rest-length springs,
/// non-proportional damping of links, bouncing bodies).
[[nodiscard]] std::optional<double> exact_error(const ExactReference& reference,
                                                const Simulation& sim);

}  // namespace fixstep::cli
