// A vector of per-tick scratch: a copy takes its source's size but not its elements. Internal
// to the engine: not installed.
//
// A World's snapshot is a copy of its kernel (World::save, World::restore), and a rollback
// restores one every frame: copying arrays that every tick writes in full before it reads them
// (the disc contacts' motions, boxes and solver rows, the plane pass's motions) only spends
// memory bandwidth. Declaring such a member a ScratchVector keeps it out of the copy; the size
// still follows the source, so that a restore across a change of the disc set leaves each
// array sized for the set it restores, as before. Only for members no tick reads before it
// writes them (nor anything between ticks reads): a copy's elements are value-initialised
// (copy construction) or are the destination's own (copy assignment), which may be those of a
// later tick or of a tick a stop request interrupted.
#pragma once

#include <utility>
#include <vector>

namespace fixstep::detail {

template <class T>
class ScratchVector : public std::vector<T> {
 public:
  using std::vector<T>::vector;
  ScratchVector() = default;
  ScratchVector(const ScratchVector& other) : std::vector<T>(other.size()) {}
  ScratchVector& operator=(const ScratchVector& other) {
    if (this != &other) this->resize(other.size());
    return *this;
  }
  ScratchVector(ScratchVector&&) noexcept = default;
  ScratchVector& operator=(ScratchVector&&) noexcept = default;
  ~ScratchVector() = default;
};

}  // namespace fixstep::detail
