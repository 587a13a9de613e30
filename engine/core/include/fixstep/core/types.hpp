// Small value types shared by every fixstep module.
#pragma once

#include <cstdint>

namespace fixstep {

/// A 2D vector of doubles: the type of every public input (positions in m, velocities in m/s,
/// forces in N, accelerations in m/s^2). Bodies are stored in the scene's precision; this is
/// only the interface type.
/// The arithmetic below is component-wise IEEE-754 double, one rounding per operation (the
/// targets carry -ffp-contract=off to their users, so no a·b + c is fused): the same bits on
/// every platform, as game rules need. length() is det::hypot (det_math.hpp).
struct Vec2 {
  double x = 0.0;
  double y = 0.0;
  friend constexpr bool operator==(const Vec2&, const Vec2&) = default;

  friend constexpr Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
  friend constexpr Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
  friend constexpr Vec2 operator-(Vec2 a) { return {-a.x, -a.y}; }
  friend constexpr Vec2 operator*(double s, Vec2 a) { return {s * a.x, s * a.y}; }
  friend constexpr Vec2 operator*(Vec2 a, double s) { return {a.x * s, a.y * s}; }
  /// Divides each component by s (IEEE: s = 0 gives ±inf or NaN, as for doubles).
  friend constexpr Vec2 operator/(Vec2 a, double s) { return {a.x / s, a.y / s}; }
  constexpr Vec2& operator+=(Vec2 b) { return *this = *this + b; }
  constexpr Vec2& operator-=(Vec2 b) { return *this = *this - b; }
  constexpr Vec2& operator*=(double s) { return *this = *this * s; }
};

/// a·b = a.x b.x + a.y b.y (in the product of the operands' units).
constexpr double dot(Vec2 a, Vec2 b) {
  return a.x * b.x + a.y * b.y;
}
/// The 2D cross product a × b = a.x b.y - a.y b.x: the z component of the 3D cross product,
/// positive when b lies counter-clockwise of a.
constexpr double cross(Vec2 a, Vec2 b) {
  return a.x * b.y - a.y * b.x;
}
/// |a| = det::hypot(a.x, a.y): correctly rounded to within 0.501 ulp, without overflow for
/// large components, the same bits everywhere.
double length(Vec2 a);

/// An 8-bit-per-channel colour, straight (not premultiplied) alpha.
struct Rgba8 {
  std::uint8_t r = 0, g = 0, b = 0, a = 255;
  friend constexpr bool operator==(const Rgba8&, const Rgba8&) = default;
};

/// Floating-point precision of a world's state and arithmetic. `f32` means float arithmetic
/// throughout (as in the tables of Fiedler's "Integration Basics"); `f64` means double.
enum class Precision { f32, f64 };

}  // namespace fixstep
