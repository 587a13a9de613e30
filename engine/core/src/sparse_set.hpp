// The component storage of the world's kernel (the EnTT idea, kept minimal): every component
// type lives in its own sparse set keyed by entity slot, so adding or removing a component never
// touches the others. Internal to the engine: not installed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "fixstep/core/entity.hpp"

namespace fixstep::detail {

/// Entity slot -> dense index map with the entities in dense order (swap-and-pop removal).
struct SparseSet {
  std::vector<std::uint32_t> sparse;  ///< slot -> dense index + 1; 0 = absent
  std::vector<Entity> dense;

  [[nodiscard]] bool contains(Entity e) const {
    return !e.is_null() && e.slot() < sparse.size() && sparse[e.slot()] != 0 &&
           dense[sparse[e.slot()] - 1] == e;
  }
  [[nodiscard]] std::size_t index(Entity e) const { return sparse[e.slot()] - 1; }
  std::size_t insert(Entity e) {
    if (e.slot() >= sparse.size()) sparse.resize(e.slot() + 1, 0);
    dense.push_back(e);
    sparse[e.slot()] = static_cast<std::uint32_t>(dense.size());
    return dense.size() - 1;
  }
  /// Removes e and returns the dense index it had; the last element moved into that index.
  std::size_t erase(Entity e) {
    const std::size_t i = index(e);
    const std::size_t last = dense.size() - 1;
    if (i != last) {
      dense[i] = dense[last];
      sparse[dense[i].slot()] = static_cast<std::uint32_t>(i + 1);
    }
    dense.pop_back();
    sparse[e.slot()] = 0;
    return i;
  }
};

/// A component type stored array-of-structs: cold, authoritative data.
template <class C>
struct Store {
  SparseSet set;
  std::vector<C> data;
};

}  // namespace fixstep::detail
