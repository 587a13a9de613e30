// Disc contacts, phase 1: the tick's impacts in windows. A box swept over the whole tick covers
// a fast disc's whole path, so in a crowd of fast discs (two streams crossing, a formation, a
// scattered burst) each box overlaps hundreds of others whose paths cross it at other times:
// the candidate pairs and the predictions after every impact grow with the square of the speed.
// When the tick's boxes overlap in more than crowded_pairs pairs a disc and the discs move far
// enough that shorter boxes part them, the impacts run over equal windows of the tick in turn:
// each window pairs the discs by their boxes over it (on their motions at its start, with what an
// impact changes within it paired as in disc_reach.cpp), predicts their first events from its
// start, and resolves the impacts due within it; events with walls carry over from window to
// window. The events and their order are those of one window over the tick: a pair that meets
// within a window overlaps in that window's boxes.
#include <algorithm>
#include <cmath>

#include "disc_contacts.hpp"
#include "fixstep/core/limits.hpp"

namespace fixstep::detail {

template <class Real>
int DiscContacts<Real>::motion_windows() const {
  double most = 0.0;  // the largest motion over the tick, in radii of its disc
  live_range(0, live_count(), [&](std::uint32_t k) {
    const SweptBox& b = boxes_[k];
    const double pad = box_pad(discs_[k]);
    const double motion = std::max(b.max_x - b.min_x, b.max_y - b.min_y) - 2.0 * pad;
    if (std::isfinite(motion)) most = std::max(most, motion / discs_[k].radius);
  });
  const double windows = std::ceil(most / window_radii);
  return windows >= max_windows ? max_windows : std::max(1, static_cast<int>(windows));
}

template <class Real>
int DiscContacts<Real>::tick_windows(const Tick& tick, ContactStats& stats) {
  const std::size_t n = discs_.size();
  const int windows = motion_windows();
  if (windows > 1) return find_candidates(tick, stats, crowded_pairs * n, true) ? 1 : windows;
  return find_candidates(tick, stats, max_candidate_pairs(n), true) ? 1 : 0;
}

template <class Real>
void DiscContacts<Real>::window_boxes(const Tick& tick, double t0, double t1) {
  halves(live_count(), [&](std::size_t begin, std::size_t end, int) {
    live_range(begin, end, [&](std::uint32_t k) {
      const double pad = box_pad(discs_[k]);
      // A disc the plane pass bounced is on its free motion until its first plane event, while
      // nothing changed its motion (disc_events.cpp, switch_to_plane_motion()).
      const std::int32_t slot = discs_[k].plane_slot;
      const bool free = slot >= 0 && tick.after_t[slot] >= 0.0 && stamp_[k] == 0;
      const double until = free ? std::clamp(tick.after[slot].first, t0, t1) : t1;
      boxes_[k] = path_box(motion_[k], t0, until, pad);
      // From the first plane event on: the plane pass's motion (as plane_box() covers it).
      if (free && until < t1)
        add_plane_motion(tick.after[slot], tick.after_t[slot], until, t1, pad, boxes_[k]);
    });
  });
}

}  // namespace fixstep::detail
