// Disc contacts, phase 1: the tick's candidate pairs, each pair of discs whose boxes over the
// tick overlap (the broadphase, grid_broadphase.hpp, or the pairs recycled from the fat boxes,
// disc_fat.cpp), less the linked and filtered pairs, and each disc's list of its pairs.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "disc_contacts.hpp"
#include "fixstep/core/limits.hpp"
#include "fixstep/core/step_results.hpp"

namespace fixstep::detail {

template <class Real>
bool DiscContacts<Real>::find_candidates(const Tick& tick, ContactStats& stats,
                                         std::size_t max_pairs, bool whole_tick) {
  const std::size_t n = discs_.size();
  const std::size_t cap = max_candidate_pairs(n);  // limits.hpp; a pile: ~3 per disc
  const std::size_t most = std::min(max_pairs, cap);
  int recycled = -1;  // the fat boxes' pairs (disc_fat.cpp), or the broadphase on the boxes
  const int threads = pass_threads(tick);
  if (whole_tick && live_all_) {
    recycled = recycled_pairs(threads, most, cap);
  } else {
    fat_.valid = false;  // the broadphase's grid is the window's or the live discs'
  }
  if (recycled == -1 ? !pairs_of(boxes_, pairs_, threads, most) : recycled == 0) {
    pairs_.clear();
    if (max_pairs < cap) return false;  // a try (tick_windows())
    stats.candidate_pairs = cap, stats.capped = 1;
    // The limit that stopped the broadphase: its candidates', or its dropped pairs' (a crowd a
    // filter or a link keeps apart); the recycled pairs' count is the candidates'.
    const bool vetoed = recycled == -1 && broadphase_.stopped_by_veto();
    cap_ = CapHit{vetoed ? "max_vetoed_pairs" : "max_candidate_pairs",
                  vetoed ? max_vetoed_pairs(n) : cap, largest_box(), CapHit::npos, 0.0};
    return false;
  }
  // Linked pairs never collide (Box2D's collideConnected = false), filtered ones neither, and
  // sensors only sense: none of them reaches the narrowphase.
  sensor_pairs_.clear();
  if (!linked_.empty() || !filters_.empty()) sort_out_pairs();
  stats.candidate_pairs = std::max(stats.candidate_pairs, pairs_.size());
  incident_lists();
  return true;
}

template <class Real>
void DiscContacts<Real>::incident_lists() {
  // Each live disc's pairs (in pair order): incident_[offset_[k] .. offset_[k] + degree_[k]).
  const auto m = static_cast<std::uint32_t>(pairs_.size());
  incident_.resize(2 * std::size_t{m});
  auto count = [&](std::uint32_t from, std::uint32_t to, std::uint32_t* degree) {
    for (std::uint32_t i = from; i < to; ++i) ++degree[pairs_[i].a], ++degree[pairs_[i].b];
  };
  auto fill = [&](std::uint32_t from, std::uint32_t to, std::uint32_t* cursor) {
    for (std::uint32_t i = from; i < to; ++i) {
      incident_[cursor[pairs_[i].a]++] = i;
      incident_[cursor[pairs_[i].b]++] = i;
    }
  };
  if (!live_all_ || !sharing() || m < min_parallel_copies) {
    const std::size_t live = live_count();
    live_range(0, live, [&](std::uint32_t k) { degree_[k] = 0; });
    count(0, m, degree_.data());
    std::uint32_t at = 0;
    live_range(0, live, [&](std::uint32_t k) {
      offset_[k] = cursor_[k] = at;  // fill cursors
      at += degree_[k];
    });
    fill(0, m, cursor_.data());
    return;
  }
  // Each thread counts and fills the lists from its half of the pairs: a disc's list holds the
  // first half's pairs, then the second's, in pair order as one thread fills it.
  const std::size_t n = discs_.size();
  degree_half_.resize(n), cursor_half_.resize(n);
  auto counts = [&](int h) {
    std::uint32_t* const degree = h == 0 ? degree_.data() : degree_half_.data();
    std::fill(degree, degree + n, 0u);
    h == 0 ? count(0, m / 2, degree) : count(m / 2, m, degree);
  };
  both_halves(counts);
  std::uint32_t at = 0;
  for (std::size_t k = 0; k < n; ++k) {
    offset_[k] = cursor_[k] = at;
    cursor_half_[k] = at + degree_[k];
    degree_[k] += degree_half_[k];
    at += degree_[k];
  }
  auto fills = [&](int h) {
    h == 0 ? fill(0, m / 2, cursor_.data()) : fill(m / 2, m, cursor_half_.data());
  };
  both_halves(fills);
}

template <class Real>
bool DiscContacts<Real>::pairs_of(std::span<const SweptBox> boxes, std::vector<DiscPair>& out,
                                  int threads, std::size_t cap) {
  if (!live_all_) {  // the live discs' boxes, in index order; their pairs mapped back
    sort_live();
    gather_live_boxes(boxes);
    const bool ok = pairs_of_boxes(live_boxes_, live_dynamic_, out, threads, cap);
    for (DiscPair& p : out) p.a = live_[p.a], p.b = live_[p.b];
    return ok;
  }
  return pairs_of_boxes(boxes, dynamic_, out, threads, cap);
}

template <class Real>
bool DiscContacts<Real>::pairs_of_boxes(std::span<const SweptBox> boxes,
                                        std::span<const std::uint8_t> dynamic,
                                        std::vector<DiscPair>& out, int threads, std::size_t cap) {
  if (linked_.empty() && filters_.empty()) {
    return broadphase_.find_pairs(boxes, dynamic, cap, out, threads);
  }
  // Linked pairs never collide (Box2D's collideConnected = false), filtered ones neither: the
  // broadphase drops them without counting them against the cap (discs a filter keeps apart
  // may all be at one point), up to max_vetoed_pairs of them.
  auto reject = [](const void* context, std::uint32_t a, std::uint32_t b) {
    const auto& self = *static_cast<const DiscContacts*>(context);
    if (!self.live_all_) a = self.live_[a], b = self.live_[b];  // live positions
    if (!self.may_collide(a, b)) return true;
    const std::uint64_t key = (std::uint64_t(a) << 32) | b;
    return !self.linked_.empty() &&
           std::binary_search(self.linked_.begin(), self.linked_.end(), key);
  };
  const GridBroadphase::PairVeto veto{reject, this, max_vetoed_pairs(discs_.size())};
  broadphase_.set_veto(&veto);
  const bool ok = broadphase_.find_pairs(boxes, dynamic, cap, out, threads);
  broadphase_.set_veto(nullptr);
  return ok;
}

template <class Real>
std::uint32_t DiscContacts<Real>::largest_box() const {
  std::uint32_t best = 0, nan = GrownBox::none;
  double widest = -1.0;
  live_range(0, live_count(), [&](std::uint32_t k) {
    const SweptBox& b = boxes_[k];
    const double w = std::max(b.max_x - b.min_x, b.max_y - b.min_y);
    if (std::isnan(w) && nan == GrownBox::none) nan = k;  // a NaN box first
    if (w > widest) widest = w, best = k;
  });
  return nan != GrownBox::none ? nan : best;
}

}  // namespace fixstep::detail
