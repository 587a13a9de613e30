// The range checks of the values a world is made of and edited with (value_ranges.hpp): each
// failure names the body or link (`who`), the field and what it must be. Internal to the
// engine's kernel: not installed.
#pragma once

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "fixstep/core/components.hpp"
#include "fixstep/core/value_ranges.hpp"

namespace fixstep::detail {

/// A value is acceptable when it is finite in double and stays finite once narrowed to Real
/// (1e39 is a fine double but +inf as a float).
template <class Real>
bool representable(double v) {
  return std::isfinite(v) && std::isfinite(static_cast<Real>(v));
}

template <class Real>
void check_value(double v, bool ok_range, const std::string& who, const char* field,
                 const char* allowed) {
  if (!representable<Real>(v) || !ok_range) {
    throw std::invalid_argument(fmt::format("{}: {} must be {} (got {})", who, field, allowed, v));
  }
}

/// A position, velocity or anchor: each component within max_state_magnitude (value_ranges.hpp).
template <class Real>
void check_vec(const Vec2& v, const std::string& who, const char* field) {
  check_value<Real>(v.x, within_state(v.x), who, field, "finite with |value| <= 1e12");
  check_value<Real>(v.y, within_state(v.y), who, field, "finite with |value| <= 1e12");
}

/// A force or an acceleration: each component within max_coefficient (value_ranges.hpp).
template <class Real>
void check_coefficients(const Vec2& v, const std::string& who, const char* field) {
  check_value<Real>(v.x, within_coefficient(v.x), who, field, "finite with |value| <= 1e100");
  check_value<Real>(v.y, within_coefficient(v.y), who, field, "finite with |value| <= 1e100");
}

/// A stiffness, damping, drag or friction: in [0, max_coefficient].
inline bool nonnegative_coefficient(double v) {
  return within_coefficient(v) && v >= 0.0;
}

/// A spring-damper's stiffness k (N/m) and damping b (N·s/m) in [0, max_coefficient] and its
/// rest length (m) in [0, max_state_magnitude]; `names` are the three fields' names in a message.
template <class Real>
void check_spring_terms(double k, double b, double rest, const std::string& who,
                        const std::array<const char*, 3>& names) {
  // isfinite first: an ordered comparison with NaN raises FE_INVALID (trapped in Debug tests).
  check_value<Real>(k, nonnegative_coefficient(k), who, names[0], "in [0, 1e100] N/m");
  check_value<Real>(b, nonnegative_coefficient(b), who, names[1], "in [0, 1e100] N*s/m");
  check_value<Real>(rest, within_state(rest) && rest >= 0.0, who, names[2], "in [0, 1e12] m");
}

}  // namespace fixstep::detail
