// The checks a program makes on a WorldDef before building it: the stability guard, the work
// limits and the overlap of discs at tick 0. World(def) makes none of them (it builds what it is
// given, as Box2D's b2CreateWorld does); fixstep's programs and its scene loader call them on
// every definition that comes from outside (a file, a command line, a game's setup).
#pragma once

#include <string>
#include <vector>

#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"

namespace fixstep {

/// The stability guard on a whole definition, at def.settings' dt, integrator and substeps:
/// check_stability (stability.hpp) for the bodies no link joins and check_linked_stability for
/// the rest. Returns its warnings, one message each (a body or network within 10 % of its bound;
/// with allow_unstable, an unstable one). Throws std::invalid_argument with the guard's first
/// finding of an unstable body or network and the smallest stable substep count ("...; stable
/// from substeps = N (dt <= H s)"), unless allow_unstable (for demos that show a blow-up on
/// purpose). Throws as check_linked_stability for links that are not def's.
[[nodiscard]] std::vector<std::string> check_stability(const WorldDef& def,
                                                       bool allow_unstable = false);

/// Throws LimitError (limits.hpp) when one tick of def's world would exceed max_tick_work or its
/// implicit solve max_implicit_bodies or max_implicit_solve_bytes: check_world_limits of def.
void check_limits(const WorldDef& def);

/// Throws std::invalid_argument naming both bodies ("body 'a' and body 'b' overlap by D m at
/// tick 0 ...") when two discs that may touch overlap where they start in a world with contacts
/// (first_disc_overlap, disc_overlap.hpp); nothing without contacts.
void check_overlaps(const WorldDef& def);

/// The three checks in the order fixstep's programs make them: overlaps, limits (before the
/// guard's power iteration, which they bound), then the stability guard. Returns the guard's
/// warnings; throws as each check.
[[nodiscard]] std::vector<std::string> check_definition(const WorldDef& def,
                                                        bool allow_unstable = false);

}  // namespace fixstep
