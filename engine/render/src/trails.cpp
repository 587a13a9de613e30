#include "fixstep/trails.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

#include "fixstep/detail/defined_entity.hpp"

namespace fixstep {

void Trails::grow(std::uint32_t slot) {
  const std::size_t n = std::size_t{slot} + 1;
  generation_.resize(n, 0);
  seen_.resize(n, 0);
  head_.resize(n, 0);
  count_.resize(n, 0);
  x_.resize(n * capacity, 0.0f);
  y_.resize(n * capacity, 0.0f);
}

void Trails::record(const RenderFrame& frame) {
  const std::size_t n = frame.x.size();
  if (!frame.ids.empty() && frame.ids.size() != n) {
    throw std::invalid_argument(
        fmt::format("RenderFrame has {} ids for {} bodies (Trails::record)", frame.ids.size(), n));
  }
  const std::uint32_t previous = stamp_++;
  slot_of_.resize(n);
  for (std::size_t j = 0; j < n; ++j) {
    const Entity e = frame.ids.empty() ? detail::defined_entity(j) : frame.ids[j];
    if (e.is_null())
      throw std::invalid_argument(fmt::format("RenderFrame: body {} has a null id", j));
    const std::uint32_t s = e.slot();
    if (s >= generation_.size()) grow(s);
    if (generation_[s] != e.generation || seen_[s] != previous) {  // a body new to the trails
      generation_[s] = e.generation;
      head_[s] = 0;
      count_[s] = 0;
    }
    seen_[s] = stamp_;
    const std::size_t at = std::size_t{s} * capacity + head_[s];
    x_[at] = frame.x[j];
    y_[at] = frame.y[j];
    head_[s] = static_cast<std::uint8_t>((head_[s] + 1) % capacity);
    count_[s] = static_cast<std::uint8_t>(std::min(count_[s] + 1, capacity));
    slot_of_[j] = s;
  }
}

void Trails::clear() {
  ++stamp_;  // nothing was seen in the record before the next one
  slot_of_.clear();
}

int Trails::samples(std::size_t j, std::span<float, capacity> xs,
                    std::span<float, capacity> ys) const {
  const std::uint32_t s = slot_of_[j];
  const int count = count_[s];
  // The ring holds `count` samples ending before head_: oldest first, the `older` ones from
  // `oldest` to the end of the ring, then the rest from its start.
  const int oldest = (head_[s] - count + capacity) % capacity;
  const int older = std::min(count, capacity - oldest);
  const float* tx = &x_[std::size_t{s} * capacity];
  const float* ty = &y_[std::size_t{s} * capacity];
  std::copy_n(tx + oldest, older, xs.begin());
  std::copy_n(tx, count - older, xs.begin() + older);
  std::copy_n(ty + oldest, older, ys.begin());
  std::copy_n(ty, count - older, ys.begin() + older);
  return count;
}

}  // namespace fixstep
