#include "fixstep/core/components.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace fixstep {

namespace {
void require(bool ok, const char* what, const char* allowed, double v) {
  if (!ok) throw std::invalid_argument(fmt::format("{} must be {} (got {})", what, allowed, v));
}
}  // namespace

LinkSpring spring_from_frequency(double frequency_hz, double damping_ratio, double mass) {
  require(std::isfinite(frequency_hz) && frequency_hz > 0.0, "frequency", "finite and > 0 Hz",
          frequency_hz);
  require(std::isfinite(damping_ratio) && damping_ratio >= 0.0, "damping_ratio", "finite and >= 0",
          damping_ratio);
  require(std::isfinite(mass) && mass > 0.0, "mass", "finite and > 0 kg", mass);
  const double omega = 2.0 * std::numbers::pi * frequency_hz;
  return LinkSpring{.stiffness = mass * omega * omega,
                    .damping = 2.0 * mass * damping_ratio * omega,
                    .rest_length = 0.0};
}

const char* body_type_name(BodyType type) {
  switch (type) {
    case BodyType::static_body:
      return "static";
    case BodyType::kinematic:
      return "kinematic";
    case BodyType::dynamic:
      break;
  }
  return "dynamic";
}

double reduced_mass(double mass_a, double mass_b) {
  require(std::isfinite(mass_a) && mass_a > 0.0, "mass_a", "finite and > 0 kg", mass_a);
  require(std::isfinite(mass_b) && mass_b > 0.0, "mass_b", "finite and > 0 kg", mass_b);
  return mass_a * mass_b / (mass_a + mass_b);
}

}  // namespace fixstep
