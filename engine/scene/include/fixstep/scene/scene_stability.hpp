// The stability guard applied to a scene file: the core guard's findings (stability.hpp),
// located at the scene's lines and keys, with what to change in the file.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "fixstep/core/definition_checks.hpp"
#include "fixstep/core/stability.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/scene/scene.hpp"

namespace fixstep {

/// The stability guard's refusal of scene.def (what World(scene.def) throws) located in the
/// file: a SceneError at the line and key of the unstable body ("body[i]"), or, for a network,
/// of its stiffest link (the strongest damper's when the damping flow binds; the fastest
/// body's "body[i]" without either), whose message ends with what to change in the file: "use
/// substeps = N in [world] (or dt <= H s), or set allow_unstable = true", another integrator
/// when no step is stable, or other masses and stiffnesses when they overflow a double.
[[nodiscard]] SceneError located(const Scene& scene, const UnstableDefinition& e);

/// The guard's findings on scene.def that did not refuse it (World::warnings(): near-limit
/// bodies and networks, allowed instabilities with what would make them stable), located as
/// located() locates a refusal, each "FILE:LINE: KEY: MESSAGE".
[[nodiscard]] std::vector<std::string> located_warnings(const Scene& scene,
                                                        std::span<const StabilityFinding> findings);

/// The runtime guard's message for `fault` in a simulation built from `scene` (bodies in scene
/// order): "FILE:LINE: " and the core explain_fault() (stability.hpp) of the scene's bodies,
/// links and settings, one line.
[[nodiscard]] std::string explain_fault(const Scene& scene, const StateFault& fault);

}  // namespace fixstep
