#include "fixstep/rewind.hpp"

#include <stdexcept>

namespace fixstep {

RewindBuffer::RewindBuffer(std::size_t capacity) {
  if (capacity == 0) throw std::invalid_argument("rewind buffer: capacity must be >= 1 tick");
  slots_.resize(capacity);
}

void RewindBuffer::push(const Simulation& sim) {
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
