// Entity handles: values, not pointers (the Box2D v3 / EnTT idea).
#pragma once

#include <cstdint>

namespace fixstep {

/// A handle to an entity in a World. `index1` is the slot index plus one, so a
/// zero-initialised Entity is the null handle; `generation` increases every time a slot is
/// reused, so a handle to a destroyed entity is detected instead of aliasing its successor.
struct Entity {
  std::uint32_t index1 = 0;
  std::uint32_t generation = 0;

  [[nodiscard]] constexpr bool is_null() const { return index1 == 0; }
  [[nodiscard]] constexpr std::uint32_t slot() const { return index1 - 1; }
  friend constexpr bool operator==(const Entity&, const Entity&) = default;
};

/// A handle to a joint (JointDef: a hinge, slider, weld, rope, wheel or motor between two
/// bodies with shapes) in a World: slot index plus one and generation, like Entity; zero is
/// the null joint. Destroying either body destroys the joint, and the handle becomes stale.
struct Joint {
  std::uint32_t index1 = 0;
  std::uint32_t generation = 0;

  [[nodiscard]] constexpr bool is_null() const { return index1 == 0; }
  [[nodiscard]] constexpr std::uint32_t slot() const { return index1 - 1; }
  friend constexpr bool operator==(const Joint&, const Joint&) = default;
};

/// The null entity (all zeros).
inline constexpr Entity null_entity{};

/// A handle to a link (a spring-damper between two bodies) in a World: slot index plus one
/// and generation, like Entity; zero is the null link. Destroying either body destroys the
/// link, and the handle becomes stale.
struct Link {
  std::uint32_t index1 = 0;
  std::uint32_t generation = 0;

  [[nodiscard]] constexpr bool is_null() const { return index1 == 0; }
  [[nodiscard]] constexpr std::uint32_t slot() const { return index1 - 1; }
  friend constexpr bool operator==(const Link&, const Link&) = default;
};

}  // namespace fixstep
