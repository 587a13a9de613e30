// TEMPORARY: sort-and-sweep stand-in until disc_broadphase lands.
#pragma once

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <span>
#include <vector>

namespace fixstep::detail {

struct SweptBox {
  double min_x, min_y, max_x, max_y;
};
struct DiscPair {
  std::uint32_t a, b;
};

class DiscBroadphase {
 public:
  bool find_pairs(std::span<const SweptBox> boxes, std::span<const std::uint8_t> active,
                  std::size_t max_pairs, std::vector<DiscPair>& pairs, int /*threads*/) {
    pairs.clear();
    order_.resize(boxes.size());
    std::iota(order_.begin(), order_.end(), 0u);
    std::sort(order_.begin(), order_.end(), [&](std::uint32_t i, std::uint32_t j) {
      return boxes[i].min_x < boxes[j].min_x || (boxes[i].min_x == boxes[j].min_x && i < j);
    });
    for (std::size_t p = 0; p < order_.size(); ++p) {
      const SweptBox& bi = boxes[order_[p]];
      for (std::size_t q = p + 1; q < order_.size() && boxes[order_[q]].min_x <= bi.max_x; ++q) {
        const SweptBox& bj = boxes[order_[q]];
        if (bj.min_y > bi.max_y || bi.min_y > bj.max_y) continue;
        const std::uint32_t a = std::min(order_[p], order_[q]), b = std::max(order_[p], order_[q]);
        if (!active[a] && !active[b]) continue;
        if (pairs.size() >= max_pairs) return false;
        pairs.push_back({a, b});
      }
    }
    std::sort(pairs.begin(), pairs.end(),
              [](DiscPair l, DiscPair r) { return l.a < r.a || (l.a == r.a && l.b < r.b); });
    return true;
  }

 private:
  std::vector<std::uint32_t> order_;
};

}  // namespace fixstep::detail
