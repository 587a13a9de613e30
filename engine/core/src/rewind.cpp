#include "fixstep/core/rewind.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace fixstep {

std::size_t rewind_capacity(double seconds, double dt, std::size_t state_bytes,
                            std::size_t max_bytes) {
  if (!(std::isfinite(seconds) && seconds >= 0.0 && std::isfinite(dt) && dt > 0.0)) {
    throw std::invalid_argument(fmt::format(
        "rewind capacity: {} s of ticks of {} s (need seconds >= 0, dt > 0)", seconds, dt));
  }
  // A span of more ticks than any buffer could hold is capped by the memory anyway.
  const double ticks = std::min(std::ceil(seconds / dt), 1e15);
  std::size_t capacity = static_cast<std::size_t>(ticks);
  if (state_bytes > 0) capacity = std::min(capacity, max_bytes / state_bytes);
  return std::max<std::size_t>(capacity, 1);
}

RewindBuffer::RewindBuffer(std::size_t capacity) {
  if (capacity == 0) throw std::invalid_argument("rewind buffer: capacity must be >= 1 tick");
  slots_.resize(capacity);
}

void RewindBuffer::push(const World& sim) {
  newest_ = size_ == 0 ? 0 : (newest_ + 1) % slots_.size();
  sim.save(slots_[newest_]);
  if (size_ < slots_.size()) ++size_;
}

const WorldSnapshot* RewindBuffer::step_back() {
  if (size_ < 2) return nullptr;
  newest_ = (newest_ + slots_.size() - 1) % slots_.size();
  --size_;
  return &slots_[newest_];
}

std::uint64_t RewindBuffer::oldest_tick() const {
  if (size_ == 0) return 0;
  return slots_[(newest_ + slots_.size() - (size_ - 1)) % slots_.size()].tick();
}

}  // namespace fixstep
