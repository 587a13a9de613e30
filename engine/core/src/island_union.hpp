// The union-find of the sleeping islands (world_sleep.cpp, world_shape_sleep.cpp): each body's
// parent, the smaller index the root, so an island's root is its smallest body index.
#pragma once

#include <cstdint>
#include <vector>

namespace fixstep::detail {

inline std::uint32_t find_root(std::vector<std::uint32_t>& parent, std::uint32_t j) {
  while (parent[j] != j) j = parent[j] = parent[parent[j]];  // path halving
  return j;
}

inline void join(std::vector<std::uint32_t>& parent, std::uint32_t a, std::uint32_t b) {
  a = find_root(parent, a), b = find_root(parent, b);
  if (a < b) parent[b] = a;
  if (b < a) parent[a] = b;
}

}  // namespace fixstep::detail
