#include "fixstep/scene/scene_stability.hpp"

#include <fmt/format.h>

#include <cmath>

#include "fixstep/core/defined_bodies.hpp"
#include "fixstep/core/float_mode.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/world_settings.hpp"

namespace fixstep {

std::vector<BodyStability> check_stability(const Scene& scene) {
  return check_stability(scene.bodies, scene.settings.integrator, scene.settings.dt,
                         scene.settings.substeps);
}

std::optional<NetworkStability> check_scene_network(const Scene& scene) {
  return check_linked_stability(scene.bodies, scene.links, scene.settings.integrator,
                                scene.settings.dt, scene.settings.substeps);
}

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

std::vector<std::string> enforce_stability(const Scene& scene) {
  const IeeeFloatMode ieee;  // the same verdict whatever the caller's FPU mode
  std::vector<std::string> warnings;
  const int substeps = scene.settings.substeps;
  auto apply = [&](Stability verdict, std::size_t line, const std::string& key,
                   const std::string& message, const std::string& advised) {
    if (verdict == Stability::unstable && !scene.allow_unstable) {
      throw SceneError(scene.file, line, 0, key, advised);
    }
    if (verdict != Stability::stable) {
      warnings.push_back(fmt::format("{}:{}: {}: {}", scene.file, line, key,
                                     verdict == Stability::unstable ? advised : message));
    }
  };
  auto body_line = [&](std::size_t i) {
    return i < scene.source.body_lines.size() ? scene.source.body_lines[i] : std::size_t{0};
  };
  // Bodies that links join are judged as a network below, not on their own.
  const std::vector<bool> linked = linked_bodies(scene.bodies.size(), scene.links);
  for (const BodyStability& r : check_stability(scene)) {
    const std::size_t i = r.body.slot();
    if (linked[i]) continue;
    apply(r.verdict, body_line(i), fmt::format("body[{}]", i), r.message,
          with_advice(r.message, r.min_substeps, r.max_step, r.radius, substeps,
                      scene.allow_unstable));
  }
  if (const std::optional<NetworkStability> net = check_scene_network(scene)) {
    const std::string advised = with_advice(net->message, net->min_substeps, net->max_step,
                                            net->radius, substeps, scene.allow_unstable);
    const std::optional<std::size_t> link =
        net->damping_bound ? net->strongest_damper : net->stiffest_link;
    if (link) {
      const std::size_t line =
          *link < scene.source.link_lines.size() ? scene.source.link_lines[*link] : 0;
      const bool named =
          *link < scene.source.link_keys.size() && !scene.source.link_keys[*link].empty();
      apply(net->verdict, line,
            named ? scene.source.link_keys[*link] : fmt::format("link[{}]", *link), net->message,
            advised);
    } else {
      const std::size_t i = net->fastest_body.slot();
      apply(net->verdict, body_line(i), fmt::format("body[{}]", i), net->message, advised);
    }
  }
  return warnings;
}

std::string explain_fault(const Scene& scene, const StateFault& fault) {
  const auto i = fixstep::defined_index(fault.body, scene.bodies.size());
  const std::size_t line =
      i && *i < scene.source.body_lines.size() ? scene.source.body_lines[*i] : 0;
  return fmt::format("{}{}: {}", scene.file, line ? fmt::format(":{}", line) : std::string(),
                     explain_fault(scene.bodies, scene.links, scene.settings, fault));
}

}  // namespace fixstep
