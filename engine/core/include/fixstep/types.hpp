// Small value types shared by every fixstep module.
#pragma once

#include <cstdint>

namespace fixstep {

/// A 2D vector of doubles: the type of every public input (positions in m, velocities in m/s,
/// forces in N, accelerations in m/s^2). Bodies are stored in the scene's precision; this is
/// only the interface type.
struct Vec2 {
  double x = 0.0;
  double y = 0.0;
  friend constexpr bool operator==(const Vec2&, const Vec2&) = default;
};

/// An 8-bit-per-channel colour, straight (not premultiplied) alpha.
struct Rgba8 {
  std::uint8_t r = 0, g = 0, b = 0, a = 255;
  friend constexpr bool operator==(const Rgba8&, const Rgba8&) = default;
};

/// Floating-point precision of a world's state and arithmetic. `f32` means float arithmetic
/// throughout (as in the tables of Fiedler's "Integration Basics"); `f64` means double.
enum class Precision { f32, f64 };

}  // namespace fixstep
