// What a copy of some vectors allocates on the heap: each one's size in elements times the
// element's size, not its capacity (a copied vector allocates only what it holds). For
// World::snapshot_bytes and the bytes() of the parts a world copies. Internal to the engine.
#pragma once

#include <cstddef>

namespace fixstep::detail {

/// Σ v.size() · sizeof(element) over `vectors` (bytes).
template <class... Vectors>
[[nodiscard]] std::size_t copy_bytes(const Vectors&... vectors) {
  return (std::size_t{0} + ... + (vectors.size() * sizeof(typename Vectors::value_type)));
}

}  // namespace fixstep::detail
