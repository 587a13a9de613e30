// How the scene writer spells values: every number the shortest text that reads back as the
// same double, points, filter bits, strings; a body's shape keys (scene_shapes.cpp) and the
// joints' tables (scene_joints.cpp). Internal to the engine: not installed.
#pragma once

#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/world_def.hpp"

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

/// A colour as the loader reads it: "#rrggbb" when opaque, else "#rrggbbaa".
inline std::string toml_color(Rgba8 c) {
  return c.a == 255 ? fmt::format("\"#{:02x}{:02x}{:02x}\"", c.r, c.g, c.b)
                    : fmt::format("\"#{:02x}{:02x}{:02x}{:02x}\"", c.r, c.g, c.b, c.a);
}

/// s as a TOML basic string: quotes, backslashes and control characters escaped, every other
/// byte as it is (a name must be UTF-8, as TOML requires; the loader refuses it otherwise).
inline std::string toml_string(std::string_view s) {
  std::string out = "\"";
  for (const char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (c == '\n') {
      out += "\\n";
    } else if (u < 0x20 || u == 0x7f) {
      out += fmt::format("\\u{:04x}", u);
    } else {
      out += c;
    }
  }
  return out + '"';
}

/// The shape keys of body b for its [[body]] table: `inertia` when set, then a [[body.shape]]
/// table for each shape with every key that is not the loader's default (so that it loads
/// back with the same bits). Empty for a body without shapes. Goes last in the body's text:
/// the keys after a [[body.shape]] header are the shape's.
[[nodiscard]] std::string shapes_text(const BodyDef& b);

/// A [[joint]] table for each of def's joints, in order (scene_joints.cpp): its type, its bodies
/// by their names in the file (`names`, as the writer gives them; none for the world), its name
/// when not empty, then every field that is not JointDef's default (the anchor and the axis
/// always where the type uses them; a distance joint's anchor_b always, unset written as the
/// anchor). Throws std::invalid_argument "format_scene: joint[i]: ..." for a body handle that
/// is neither null nor one of def's bodies.
[[nodiscard]] std::string joints_text(const WorldDef& def, const std::vector<std::string>& names);

}  // namespace fixstep::scene_detail
