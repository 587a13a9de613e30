// The exact solution a scene's run is measured against, shared by `run` (exact_error=) and
// `compare` (each tile's error), so both print the same digits for the same state.
#pragma once

#include <cstdint>
#include <fixstep/core/components.hpp>
#include <fixstep/core/exact.hpp>
#include <fixstep/core/world.hpp>
#include <fixstep/scene/scene.hpp>
#include <optional>
#include <string>
#include <vector>

namespace fixstep::cli {

/// Which bodies a disc-disc contact has touched in a run, and from which tick: the exact
/// solutions know no contacts, so such a body has no exact state from that tick on. Fed after
/// every tick (after_tick) from what the world reports of that tick: the impacts resolved at
/// their time (World::impacts()) and the pairs that began touching
/// (World::contacts_begun(): resting contacts, discs that came to touch without an impact,
/// pairs that struck and parted within the tick, and pairs already touching at tick 0, which
/// begin in tick 1). Only dynamic bodies are marked: a static or kinematic disc moves as it
/// would untouched. A body joined by links to a touched body is touched too (the whole
/// connected component), from the same tick. Contacts with planes are not tracked here: a
/// collider in a scene with planes has no exact solution at all (ExactReference).
class TouchedBodies {
 public:
  /// For a run of `scene` (its bodies in order, its links), none touched.
  explicit TouchedBodies(const Scene& scene);
  /// Records the contacts of the tick `sim` has just stepped (sim.tick()): O(contacts of the
  /// tick), nothing once every dynamic body is touched; no allocation.
  void after_tick(const World& sim);
  /// The tick from which body j has no exact state (the first tick a contact touched it or a
  /// body linked to it), or nullopt when none has.
  [[nodiscard]] std::optional<std::uint64_t> since(std::size_t j) const {
    return since_[j] != 0 ? std::optional(since_[j]) : std::nullopt;
  }
  /// The first tick a contact touched some body, or nullopt.
  [[nodiscard]] std::optional<std::uint64_t> first() const {
    return first_ != 0 ? std::optional(first_) : std::nullopt;
  }
  /// Bodies touched so far.
  [[nodiscard]] std::size_t count() const { return count_; }
  /// None touched (a restart at tick 0).
  void clear();

 private:
  void touch(std::size_t j, std::uint64_t tick);

  std::vector<std::uint64_t> since_;    ///< per body: the tick it was touched, 0 = never
  std::vector<std::size_t> component_;  ///< per body: its link component's first body
  std::vector<std::size_t> next_;       ///< per body: the next body of its component (a ring)
  std::vector<std::uint8_t> dynamic_;   ///< per body: 1 when dynamic
  std::uint64_t first_ = 0;
  std::size_t count_ = 0;
  std::size_t dynamic_count_ = 0;
};

/// Most bodies joined by links that ExactReference solves exactly: the network's solution is a
/// dense eigen-decomposition (O(n^2) memory, O(n^3) time: 10^4 bodies took over a minute and
/// 1.7 GB, 9·10^4 would ask for 65 GB), so a larger network has no exact solution.
inline constexpr std::size_t max_exact_network_bodies = 1000;

/// The exact solution of a scene where one exists: per body (exact::solve) when the scene has
/// no links, for the whole network (exact::LinearNetwork) when it has and they are linear
/// with proportional damping, of at most max_exact_network_bodies linked bodies. Bodies that bounce
/// on the scene's planes have none (the exact solutions know no contacts), nor has a network
/// holding one; a body a disc contact has touched has none from that tick on (TouchedBodies). Holds
/// a reference to `scene`, which must outlive it.
class ExactReference {
 public:
  explicit ExactReference(const Scene& scene);
  /// Fills out[j] with body j's exact state at t (s), or nullopt where there is none; with
  /// `touched`, also nullopt for every body touched by a contact so far.
  void at(double t, std::vector<std::optional<Body>>& out,
          const TouchedBodies* touched = nullptr) const;

 private:
  [[nodiscard]] bool bouncing(const BodyDef& b) const;

  const Scene& scene_;
  std::optional<exact::LinearNetwork> network_;
  mutable std::vector<Body> states_;
};

/// Largest position error (m) over the bodies that move (dynamic and kinematic: a static body
/// never does), |x - x_exact| at sim.time(), against the exact solution of the bodies that have
/// one (and, with `touched`, that no contact has touched); nullopt when none has (rest-length
/// springs, non-proportional damping of links, bouncing bodies, every such body touched).
[[nodiscard]] std::optional<double> exact_error(const ExactReference& reference, const World& sim,
                                                const TouchedBodies* touched = nullptr);

/// For the summary of a run: "" when no contact touched a body; else which bodies a disc
/// contact took the exact solution from, e.g. "disc contacts touched 2 of 3 bodies from tick
/// 41 on" (`bodies`: the world's body count).
[[nodiscard]] std::string touched_clause(const TouchedBodies& touched, std::size_t bodies);

}  // namespace fixstep::cli
