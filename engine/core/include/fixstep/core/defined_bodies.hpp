// The handles World(def) gives a definition's bodies, for code that names a definition's bodies
// before a world exists (scene loading, input scripts, recordings' checks, the checks on a
// definition, exact solutions). A program usually gets them from WorldDef::add_body or asks the
// world: World::defined_bodies().
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/entity.hpp"

namespace fixstep {

/// Bodies are created in order in a fresh world, so body i gets slot i at generation 1.
[[nodiscard]] constexpr Entity defined_entity(std::size_t i) {
  return Entity{static_cast<std::uint32_t>(i + 1), 1};
}

/// The place in a definition of `count` bodies of the body `e` names, when World(def) made it
/// (a body created later, or in a slot reused after a destroy, has none): the inverse of
/// defined_entity.
[[nodiscard]] constexpr std::optional<std::size_t> defined_index(Entity e, std::size_t count) {
  if (e.is_null() || e.generation != 1 || e.slot() >= count) return std::nullopt;
  return e.slot();
}

/// A link of a definition with its ends as places in the definition's body list: what the
/// checks and exact solutions that run before a world exists work on.
struct IndexLink {
  std::size_t body_a = 0;
  std::size_t body_b = 0;
  LinkSpring spring{};
};

/// The links of a definition of `bodies` bodies by place. Throws std::invalid_argument
/// ("link[I]: body S:G is not one of the definition's N bodies") for an end that is null or not
/// a handle World(def) gives; both ends on one body are left to the caller's own check.
[[nodiscard]] std::vector<IndexLink> index_links(std::span<const LinkDef> links,
                                                 std::size_t bodies);

}  // namespace fixstep
