// How the scene writer spells values: every number the shortest text that reads back as the
// same double, points, filter bits; and a body's shape keys (scene_shapes.cpp). Internal to the
// engine: not installed.
#pragma once

#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <string>

#include "fixstep/core/components.hpp"

namespace fixstep::scene_detail {

/// v as a TOML float that reads back as the same double: fmt's shortest round-trip digits,
/// with ".0" added to integral values ("-0" would read as the integer 0 and lose its sign).
/// Non-finite values are written as TOML's nan/inf, which the loader refuses with their key.
inline std::string toml_number(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  std::string s = fmt::format("{}", v);
  if (s.find_first_of(".e") == std::string::npos) s += ".0";
  return s;
}

/// [x, y], each as toml_number.
inline std::string toml_point(Vec2 v) {
  return fmt::format("[{}, {}]", toml_number(v.x), toml_number(v.y));
}

/// Filter bits as the loader reads them: hexadecimal, or the negative integer of the same 64-bit
/// two's complement when the top bit is set (TOML integers are signed).
inline std::string toml_filter_bits(std::uint64_t bits) {
  if (bits >> 63) return fmt::format("{}", static_cast<std::int64_t>(bits));
  return fmt::format("0x{:x}", bits);
}

/// The shape keys of body b for its [[body]] table: `inertia` when set, then a [[body.shape]]
/// table for each shape with every key that is not the loader's default (so that it loads
/// back with the same bits). Empty for a body without shapes. Goes last in the body's text:
/// the keys after a [[body.shape]] header are the shape's.
[[nodiscard]] std::string shapes_text(const BodyDef& b);

}  // namespace fixstep::scene_detail
