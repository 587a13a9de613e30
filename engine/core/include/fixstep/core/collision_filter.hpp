// Collision filters: which discs and shapes may touch (Box2D's b2Filter).
#pragma once

#include <cstdint>

namespace fixstep {

/// CollisionFilter::category of a disc that sets none (Box2D's B2_DEFAULT_CATEGORY_BITS).
inline constexpr std::uint64_t default_category = 1;
/// CollisionFilter::mask of a disc that sets none: every category (B2_DEFAULT_MASK_BITS).
inline constexpr std::uint64_t all_categories = ~std::uint64_t{0};

/// A disc's collision filter, Box2D's b2Filter: the categories it belongs to, the categories
/// it collides with, and a group that overrides both (should_collide()).
struct CollisionFilter {
  std::uint64_t category = default_category;  ///< bits: the categories this disc is in
  std::uint64_t mask = all_categories;        ///< bits: the categories it collides with
  /// Two discs of the same non-zero group always collide when it is positive and never when
  /// it is negative, whatever their bits; 0: no group.
  std::int32_t group = 0;
  friend bool operator==(const CollisionFilter&, const CollisionFilter&) = default;
};

/// Whether two discs' filters let them touch, Box2D's rule (b2ShouldShapesCollide): the same
/// non-zero group decides alone (positive: always, negative: never); otherwise each disc's
/// category must meet the other's mask. Disc contacts, sensors and the definition checks all
/// apply it.
[[nodiscard]] constexpr bool should_collide(const CollisionFilter& a, const CollisionFilter& b) {
  if (a.group == b.group && a.group != 0) return a.group > 0;
  return (a.category & b.mask) != 0 && (b.category & a.mask) != 0;
}

}  // namespace fixstep
