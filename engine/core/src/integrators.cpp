#include "fixstep/core/integrators.hpp"

namespace fixstep {

std::string_view integrator_name(Integrator integrator) {
  switch (integrator) {
    case Integrator::semi_implicit_euler:
      return "semi_implicit_euler";
    case Integrator::explicit_euler:
      return "explicit_euler";
    case Integrator::velocity_verlet:
      return "velocity_verlet";
    case Integrator::rk4:
      return "rk4";
    case Integrator::implicit_euler:
      return "implicit_euler";
    case Integrator::forest_ruth:
      return "forest_ruth";
  }
  return "unknown";
}

std::optional<Integrator> parse_integrator(std::string_view name) {
  for (Integrator i : all_integrators) {
    if (integrator_name(i) == name) return i;
  }
  return std::nullopt;
}

std::string_view integrator_names() {
  return "semi_implicit_euler, explicit_euler, velocity_verlet, rk4, implicit_euler, "
         "forest_ruth";
}

int integrator_order(Integrator integrator) {
  switch (integrator) {
    case Integrator::velocity_verlet:
      return 2;
    case Integrator::rk4:
    case Integrator::forest_ruth:
      return 4;
    default:
      return 1;
  }
}

int integrator_evaluations(Integrator integrator) {
  switch (integrator) {
    case Integrator::velocity_verlet:
      return 2;
    case Integrator::rk4:
      return 4;
    case Integrator::forest_ruth:
      return 6;
    default:
      return 1;
  }
}

std::string_view precision_name(Precision precision) {
  return precision == Precision::f32 ? "f32" : "f64";
}

std::optional<Precision> parse_precision(std::string_view name) {
  if (name == "f32") return Precision::f32;
  if (name == "f64") return Precision::f64;
  return std::nullopt;
}

}  // namespace fixstep
