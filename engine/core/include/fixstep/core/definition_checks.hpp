// The checks World(def) makes on a WorldDef before it builds anything: the overlap of discs at
// tick 0, the work limits and the stability guard. They run on every world a program makes, in
// that order (the limits bound the guard's power iteration); each is also callable on its own.
#pragma once

#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "fixstep/core/stability.hpp"
#include "fixstep/core/world_def.hpp"

namespace fixstep {

/// One finding of the stability guard on a definition that is not stable (near its bound, or
/// unstable): a body on its own or the network links join, with the guard's numbers, so that a
/// program can word what to change (a scene file's line, a game's setting).
struct StabilityFinding {
  Stability verdict = Stability::stable;
  /// The finding, one line: the guard's message (stability.hpp), which states the fault only.
  std::string message;
  std::optional<BodyStability> body;        ///< a body no link joins (its index: body.body)
  std::optional<NetworkStability> network;  ///< the bodies links join
};

/// What World(def) and check_stability(def) throw for a definition the stability guard finds
/// unstable when def.allow_unstable is false. what() is the finding's message, then, when some
/// substep count N makes the step stable, "; stable from substeps = N (dt <= H s)" (H the
/// largest stable dt at the definition's substeps).
class UnstableDefinition : public std::invalid_argument {
 public:
  /// `finding` unstable, of a definition stepped with `substeps` substeps a tick.
  UnstableDefinition(StabilityFinding finding, int substeps);
  /// The guard's finding (verdict unstable).
  [[nodiscard]] const StabilityFinding& finding() const noexcept { return *finding_; }

 private:
  static std::string stable_from(const StabilityFinding& f, int substeps);
  std::shared_ptr<const StabilityFinding> finding_;  // shared: an exception copies nothrow
};

/// The stability guard on a whole definition, at def.settings' dt, integrator and substeps:
/// check_stability (stability.hpp) for the bodies no link joins and check_linked_stability for
/// the rest. Returns the findings that are not stable (a body or network within 10 % of its
/// bound; with def.allow_unstable, an unstable one), bodies first. Throws UnstableDefinition
/// for the first unstable finding unless def.allow_unstable (for demos that show a blow-up on
/// purpose). Throws as check_linked_stability for links that are not def's.
[[nodiscard]] std::vector<StabilityFinding> check_stability(const WorldDef& def);

/// Throws LimitError (limits.hpp) when one tick of def's world would exceed max_tick_work or its
/// implicit solve max_implicit_bodies or max_implicit_solve_bytes: check_world_limits of def.
void check_limits(const WorldDef& def);

/// Throws std::invalid_argument naming both bodies ("body 'a' and body 'b' overlap by D m at
/// tick 0 ...") when two discs that may touch overlap where they start in a world with contacts
/// (first_disc_overlap, disc_overlap.hpp); nothing without contacts.
void check_overlaps(const WorldDef& def);

/// The three checks on their own: overlaps, limits (before the guard's power iteration, which
/// they bound), then the stability guard (World(def) makes the same, the limits before it
/// builds anything). Returns the guard's findings
/// (World::warnings()); throws as each check.
[[nodiscard]] std::vector<StabilityFinding> check_definition(const WorldDef& def);

}  // namespace fixstep
