// The stability guard applied to a scene file: the core guard's findings (stability.hpp),
// located at the scene's lines and keys, with what to change in the file.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "fixstep/core/stability.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/scene/scene.hpp"

namespace fixstep {

/// check_stability for the scene's bodies at its dt, integrator and substeps (each body on its
/// own; `body` indexes scene.bodies).
[[nodiscard]] std::vector<BodyStability> check_stability(const Scene& scene);

/// check_linked_stability for the scene (fastest_body indexes scene.bodies); std::nullopt when
/// the scene has no links.
[[nodiscard]] std::optional<NetworkStability> check_scene_network(const Scene& scene);

/// Applies the guard at scene load: throws SceneError (file, the body's line, key "body[i]")
/// for the first unstable body unless the scene sets allow_unstable = true, in which case the
/// error becomes a warning. Bodies that links join are judged by check_scene_network instead,
/// after the others: its error names the stiffest link's line and key "spring[i]" (the
/// strongest damper's when the damping flow binds; the fastest body's "body[i]" without
/// either). An unstable finding ends with what to change in the file: "Use substeps = N in
/// [world] (or dt <= H s), or set allow_unstable = true", another integrator when none is
/// stable, or other masses and stiffnesses when they overflow a double. Returns the warnings
/// (near-limit bodies and networks, allowed instabilities), each "FILE:LINE: KEY: MESSAGE".
std::vector<std::string> enforce_stability(const Scene& scene);

/// The runtime guard's message for `fault` in a simulation built from `scene` (bodies in scene
/// order): "FILE:LINE: " and the core explain_fault() (stability.hpp) of the scene's bodies,
/// links and settings, one line.
[[nodiscard]] std::string explain_fault(const Scene& scene, const StateFault& fault);

}  // namespace fixstep
