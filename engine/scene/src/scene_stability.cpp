#include "fixstep/scene/scene_stability.hpp"

#include <fmt/format.h>

#include <cmath>

#include "fixstep/core/defined_bodies.hpp"
#include "fixstep/core/float_mode.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/world_settings.hpp"

namespace fixstep {

namespace {

/// An unstable finding with what to change in the scene file: the substep count (or dt) that
/// is stable, another integrator when no step is, other masses and stiffnesses when the rates
/// overflow a double (radius infinite). The advice comes before the numbers that explain the
/// finding (the message's closing parenthesis: rates and growth), so that the first 200-odd
/// characters say what is wrong and what to do:
///   body 'b' is unstable with M at dt = 0.1 s: ω·h = 3 exceeds the stability bound 2; use
///   substeps = 2 in [world] (or dt <= 0.06667 s), or set allow_unstable = true — ω = 30 rad/s,
///   growth 6.8541x per step
/// With `allowed` (allow_unstable is set) the advice says the run goes on and what would make
/// it stable.
std::string with_advice(const std::string& message, int min_substeps, double max_step,
                        double radius, int substeps, bool allowed) {
  if (!std::isfinite(radius)) {
    return message + (allowed ? "; allowed (allow_unstable), but the run will diverge at once"
                              : "; use a larger mass or a smaller stiffness, damping or drag");
  }
  // The trailing parenthesis of the message, found by balancing from its end.
  std::string head = message, details;
  if (!message.empty() && message.back() == ')') {
    int depth = 0;
    for (std::size_t i = message.size(); i-- > 0;) {
      depth += message[i] == ')' ? 1 : message[i] == '(' ? -1 : 0;
      if (depth == 0) {
        head = message.substr(0, i > 0 && message[i - 1] == ' ' ? i - 1 : i);
        details = message.substr(i + 1, message.size() - i - 2);
        break;
      }
    }
  }
  const std::string fix =
      min_substeps > 0 ? fmt::format("substeps = {} in [world] (or dt <= {:.4g} s)", min_substeps,
                                     max_step * substeps)
                       : std::string(
                             "another integrator: semi_implicit_euler, velocity_verlet, rk4, "
                             "implicit_euler or forest_ruth");
  const std::string advice =
      allowed
          ? fmt::format("allowed (allow_unstable), so the run may diverge; {} would be stable", fix)
          : fmt::format("use {}, or set allow_unstable = true", fix);
  return fmt::format("{}; {}{}", head, advice, details.empty() ? "" : " — " + details);
}

}  // namespace

namespace {

/// Where a finding stands in the scene: the line and key of the body, or of the link that binds
/// a network (the stiffest link; the strongest damper when the damping flow binds; the fastest
/// body without either).
std::pair<std::size_t, std::string> place_of(const Scene& scene, const StabilityFinding& f) {
  auto body_place = [&](Entity body) {
    const std::size_t i = body.slot();
    const std::size_t line =
        i < scene.source.body_lines.size() ? scene.source.body_lines[i] : std::size_t{0};
    return std::pair{line, fmt::format("body[{}]", i)};
  };
  if (f.body) return body_place(f.body->body);
  const NetworkStability& net = *f.network;
  const std::optional<std::size_t> link =
      net.damping_bound ? net.strongest_damper : net.stiffest_link;
  if (!link) return body_place(net.fastest_body);
  const std::size_t line =
      *link < scene.source.link_lines.size() ? scene.source.link_lines[*link] : 0;
  const bool named =
      *link < scene.source.link_keys.size() && !scene.source.link_keys[*link].empty();
  return {line, named ? scene.source.link_keys[*link] : fmt::format("link[{}]", *link)};
}

/// The finding's message with what to change in the file (with_advice).
std::string advised(const Scene& scene, const StabilityFinding& f) {
  const int min_substeps = f.body ? f.body->min_substeps : f.network->min_substeps;
  const double max_step = f.body ? f.body->max_step : f.network->max_step;
  const double radius = f.body ? f.body->radius : f.network->radius;
  return with_advice(f.message, min_substeps, max_step, radius, scene.def.settings.substeps,
                     scene.def.allow_unstable);
}

}  // namespace

SceneError located(const Scene& scene, const UnstableDefinition& e) {
  const StabilityFinding& f = e.finding();
  const auto [line, key] = place_of(scene, f);
  return SceneError(scene.file, line, 0, key, advised(scene, f));
}

std::vector<std::string> located_warnings(const Scene& scene,
                                          std::span<const StabilityFinding> findings) {
  std::vector<std::string> warnings;
  for (const StabilityFinding& f : findings) {
    const auto [line, key] = place_of(scene, f);
    warnings.push_back(
        fmt::format("{}:{}: {}: {}", scene.file, line, key,
                    f.verdict == Stability::unstable ? advised(scene, f) : f.message));
  }
  return warnings;
}

std::string explain_fault(const Scene& scene, const StateFault& fault) {
  const auto i = fixstep::defined_index(fault.body, scene.def.bodies.size());
  const std::size_t line =
      i && *i < scene.source.body_lines.size() ? scene.source.body_lines[*i] : 0;
  return fmt::format("{}{}: {}", scene.file, line ? fmt::format(":{}", line) : std::string(),
                     explain_fault(scene.def.bodies, scene.def.links, scene.def.settings, fault));
}

}  // namespace fixstep
