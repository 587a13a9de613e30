#include "fixstep/integrators.hpp"

namespace fixstep {

std::string_view integrator_name(Integrator integrator) {
  switch (integrator) {
    case Integrator::semi_implicit_euler: return "semi_implicit_euler";
    case Integrator::explicit_euler: return "explicit_euler";
  }
  return "unknown";
}

std::optional<Integrator> parse_integrator(std::string_view name) {
  for (Integrator i : all_integrators) {
    if (integrator_name(i) == name) return i;
  }
  return std::nullopt;
}

std::string_view integrator_names() { return "semi_implicit_euler, explicit_euler"; }

std::string_view precision_name(Precision precision) {
  return precision == Precision::f32 ? "f32" : "f64";
}

std::optional<Precision> parse_precision(std::string_view name) {
  if (name == "f32") return Precision::f32;
  if (name == "f64") return Precision::f64;
  return std::nullopt;
}

}  // namespace fixstep
