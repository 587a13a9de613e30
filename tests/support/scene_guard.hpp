// The stability guard on a scene as every program meets it: World(scene.def) judges the
// definition, and the scene locates its refusal and its warnings (scene_stability.hpp). For
// tests that assert the located messages, and the guard's findings of a scene's bodies.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "fixstep/core/definition_checks.hpp"
#include "fixstep/core/stability.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/scene/scene.hpp"
#include "fixstep/scene/scene_stability.hpp"

namespace fixstep::test {

/// World(scene.def)'s judgement located in the scene: the located warnings, or the located
/// SceneError thrown for an unstable body or network.
inline std::vector<std::string> enforce_stability(const Scene& scene) {
  try {
    const World world(scene.def);
    return located_warnings(scene, world.warnings());
  } catch (const UnstableDefinition& e) {
    throw located(scene, e);
  }
}

/// World(scene.def) with the guard's refusal located in the scene (a SceneError), as every
/// program that loads a scene makes it.
inline World located_world(const Scene& scene) {
  try {
    return World(scene.def);
  } catch (const UnstableDefinition& e) {
    throw located(scene, e);
  }
}

/// check_stability (stability.hpp) of the scene's bodies at its dt, integrator and substeps.
inline std::vector<BodyStability> check_stability(const Scene& scene) {
  const WorldSettings& s = scene.def.settings;
  return fixstep::check_stability(scene.def.bodies, s.integrator, s.dt, s.substeps);
}

/// check_linked_stability (stability.hpp) of the scene; nullopt without links.
inline std::optional<NetworkStability> check_scene_network(const Scene& scene) {
  const WorldSettings& s = scene.def.settings;
  return check_linked_stability(scene.def.bodies, scene.def.links, s.integrator, s.dt, s.substeps);
}

}  // namespace fixstep::test
