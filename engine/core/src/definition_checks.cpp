// The checks on a definition before it is built (definition_checks.hpp).
#include "fixstep/core/definition_checks.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "fixstep/core/disc_overlap.hpp"
#include "fixstep/core/float_mode.hpp"
#include "fixstep/core/limits.hpp"
#include "fixstep/core/stability.hpp"

namespace fixstep {

std::vector<std::string> check_stability(const WorldDef& def, bool allow_unstable) {
  const IeeeFloatMode ieee;  // the same verdict whatever the caller's FPU mode
  std::vector<std::string> warnings;
  const WorldSettings& s = def.settings;
  auto refuse = [&](const std::string& message, int min_substeps, double max_step) {
    throw std::invalid_argument(min_substeps > 0
                                    ? fmt::format("{}; stable from substeps = {} (dt <= {:.4g} s)",
                                                  message, min_substeps, max_step * s.substeps)
                                    : message);
  };
  const std::vector<bool> linked = linked_bodies(def.bodies.size(), def.links);
  for (const BodyStability& r : check_stability(def.bodies, s.integrator, s.dt, s.substeps)) {
    if (linked[r.body.slot()] || r.verdict == Stability::stable) continue;
    if (r.verdict == Stability::unstable && !allow_unstable) {
      refuse(r.message, r.min_substeps, r.max_step);
    }
    warnings.push_back(r.message);
  }
  const auto net = check_linked_stability(def.bodies, def.links, s.integrator, s.dt, s.substeps);
  if (net && net->verdict != Stability::stable) {
    if (net->verdict == Stability::unstable && !allow_unstable) {
      refuse(net->message, net->min_substeps, net->max_step);
    }
    warnings.push_back(net->message);
  }
  return warnings;
}

void check_limits(const WorldDef& def) {
  check_world_limits(def.bodies, def.links, def.planes, def.settings);
}

void check_overlaps(const WorldDef& def) {
  const auto pair = first_disc_overlap(def);
  if (!pair) return;
  const auto name = [&](std::size_t i) {
    return def.bodies[i].name.empty() ? fmt::format("body {}", i)
                                      : fmt::format("body '{}'", def.bodies[i].name);
  };
  throw std::invalid_argument(fmt::format(
      "{} and {} overlap by {:g} m at tick 0 (discs of a world with contacts must start "
      "apart or touching)",
      name(pair->first), name(pair->second),
      disc_overlap_depth(def.bodies[pair->first], def.bodies[pair->second])));
}

std::vector<std::string> check_definition(const WorldDef& def, bool allow_unstable) {
  check_overlaps(def);
  check_limits(def);
  return check_stability(def, allow_unstable);
}

}  // namespace fixstep
