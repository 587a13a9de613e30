// Disc contacts, phase 1: a tick's candidate pairs recycled from fat boxes. Box2D keeps each
// shape's box enlarged by a margin (b2_aabbMargin) in its tree, and its pairs while the shape's
// box stays inside; fixstep's broadphase is rebuilt every tick instead (grid_broadphase.hpp),
// about a sixth of a settled pile's tick. So the broadphase runs on each disc's box widened by
// FatBoxes::margin of its radius, and while every disc's box over the tick stays inside its fat
// box, the tick's pairs are the fat pairs whose boxes overlap: two boxes that overlap lie in fat
// boxes that overlap, so the filter keeps exactly the broadphase's pairs (under the same flags
// and filters: a disc falling asleep or waking forgets the fat boxes), in its order. A rebuild
// that served a single tick, or whose pairs passed the limit, rests the fat boxes for
// FatBoxes::rest_first ticks, twice as long for each such rebuild in a row, and a tick in which
// some disc moves more than the margin builds none (a gas: its discs move about their radius a
// tick). Windows of the tick and ticks that visit the live discs only run the broadphase on their
// own boxes. Within the tick, reach() asks the grid of the fat boxes, each disc there checked by
// its own box.
#include <algorithm>
#include <cassert>

#include "disc_contacts.hpp"

namespace fixstep::detail {

template <class Real>
int DiscContacts<Real>::recycled_pairs(int threads, std::size_t max_pairs, std::size_t cap) {
  FatBoxes& f = fat_;
  const std::size_t n = discs_.size();
  bool inside = f.valid && f.boxes.size() == n;
  if (inside) {  // every box within its fat box: by halves on two threads
    bool within[2] = {true, true};
    halves_from(n, min_parallel_copies, [&](std::size_t begin, std::size_t end, int half) {
      bool all = true;
      for (std::size_t k = begin; all && k < end; ++k) all = box_within(boxes_[k], f.boxes[k]);
      within[half] = all;
    });
    inside = within[0] && within[1];
  }
  if (!inside) {
    if (!f.left()) return -1;  // built for one tick: rest a while, longer each time
    // A disc that moves more than the margin in a tick leaves its fat box in the next one.
    for (std::size_t k = 0; k < n; ++k) {
      const SweptBox& b = boxes_[k];
      const double pad = box_pad(discs_[k]);
      if (std::max(b.max_x - b.min_x, b.max_y - b.min_y) - 2.0 * pad >
          FatBoxes::margin * discs_[k].radius) {
        return -1;
      }
    }
    f.boxes.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
      const double m = FatBoxes::margin * discs_[k].radius;
      const SweptBox& b = boxes_[k];
      f.boxes[k] = SweptBox{b.min_x - m, b.min_y - m, b.max_x + m, b.max_y + m};
    }
    fat_grid_.value = true;
    if (!pairs_of_boxes(f.boxes, dynamic_, f.pairs, threads, cap)) {
      f.rest_longer();  // crowded: the grid of the fat boxes cost a tick's broadphase
      return -1;
    }
    f.valid = true, f.age = 0;
  }
  ++f.age;
  const std::size_t m = f.pairs.size();
  if (sharing() && m >= min_parallel_copies) {  // each half of the fat pairs, then in order
    fat_half_.clear();
    auto job = [&](int half) {
      half == 0 ? f.overlapping(boxes_, pairs_, 0, m / 2)
                : f.overlapping(boxes_, fat_half_, m / 2, m);
    };
    both_halves(job);
    pairs_.insert(pairs_.end(), fat_half_.begin(), fat_half_.end());
  } else {
    f.overlapping(boxes_, pairs_, 0, m);
  }
  return pairs_.size() <= max_pairs ? 1 : 0;
}

template <class Real>
void DiscContacts<Real>::rebuild_fat_grid(int threads) {
  // The same boxes, flags and filters as when the fat pairs were found under this cap: the same
  // grid and pairs, so it cannot stop at the cap.
  [[maybe_unused]] const bool ok =
      pairs_of_boxes(fat_.boxes, dynamic_, fat_.pairs, threads, max_candidate_pairs(discs_.size()));
  assert(ok);
  fat_grid_.value = true;
}

}  // namespace fixstep::detail
