// The checks on a definition before it is built (definition_checks.hpp).
#include "fixstep/core/definition_checks.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "fixstep/core/disc_overlap.hpp"
#include "fixstep/core/float_mode.hpp"
#include "fixstep/core/limits.hpp"
#include "fixstep/core/stability.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "stability_verdict.hpp"

namespace fixstep {

UnstableDefinition::UnstableDefinition(StabilityFinding finding, int substeps)
    : std::invalid_argument(finding.message + stable_from(finding, substeps)),
      finding_(std::make_shared<const StabilityFinding>(std::move(finding))) {}

std::string UnstableDefinition::stable_from(const StabilityFinding& f, int substeps) {
  const int min_substeps = f.body ? f.body->min_substeps : f.network ? f.network->min_substeps : 0;
  const double max_step = f.body ? f.body->max_step : f.network ? f.network->max_step : 0.0;
  return detail::stable_from(min_substeps, max_step, substeps);
}

std::vector<StabilityFinding> check_stability(const WorldDef& def) {
  const IeeeFloatMode ieee;  // the same verdict whatever the caller's FPU mode
  std::vector<StabilityFinding> findings;
  const WorldSettings& s = def.settings;
  auto judged = [&](StabilityFinding f) {
    if (f.verdict == Stability::unstable && !def.allow_unstable) {
      throw UnstableDefinition(std::move(f), s.substeps);
    }
    findings.push_back(std::move(f));
  };
  const std::vector<bool> linked = linked_bodies(def.bodies.size(), def.links);
  for (const BodyStability& r : check_stability(def.bodies, s.integrator, s.dt, s.substeps)) {
    if (linked[r.body.slot()] || r.verdict == Stability::stable) continue;
    StabilityFinding f{.verdict = r.verdict, .message = r.message, .body = r, .network = {}};
    judged(std::move(f));
  }
  const auto net = check_linked_stability(def.bodies, def.links, s.integrator, s.dt, s.substeps);
  if (net && net->verdict != Stability::stable) {
    StabilityFinding f{
        .verdict = net->verdict, .message = net->message, .body = {}, .network = net};
    judged(std::move(f));
  }
  return findings;
}

void check_limits(const WorldDef& def) {
  check_world_limits(def.bodies, def.links, def.planes, def.settings, def.segments);
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

std::vector<StabilityFinding> check_definition(const WorldDef& def) {
  check_overlaps(def);
  check_limits(def);
  return check_stability(def);
}

}  // namespace fixstep
