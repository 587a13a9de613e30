// One queue of a tick's disc impacts and what its impacts make (disc_queue.cpp, disc_reach.cpp):
// the events in time order, the impact log, reach()'s extra pairs and grown boxes with their
// grid, and the discs held. A tick's impacts run in one lane; on two threads, the pairs' groups
// may run in two (disc_lanes.cpp), each changing only its own discs. Internal to the engine: not
// installed.
#pragma once

#include <atomic>
#include <cstdint>
#include <utility>
#include <vector>

#include "disc_paths.hpp"
#include "disc_records.hpp"
#include "fixstep/core/step_results.hpp"
#include "grown_grid.hpp"
#include "scratch_vector.hpp"

namespace fixstep::detail {

/// The predictions after impacts so far, at most cap (max_tick_predictions), and where the
/// last stop poll was (again / 2^16).
struct EventBudget {
  std::uint64_t again = 0, polled = 0, cap = 0;
};

/// Whether either of two lanes has stopped: set by one thread, read by both while they run.
/// A copy (a snapshot) starts clear; nothing runs then.
class LanesMet {
 public:
  LanesMet() = default;
  LanesMet(const LanesMet& /*other*/) noexcept {}
  LanesMet& operator=(const LanesMet& /*other*/) noexcept {
    clear();
    return *this;
  }
  ~LanesMet() = default;
  void clear() { met_.store(false, std::memory_order_relaxed); }
  void set() { met_.store(true, std::memory_order_relaxed); }
  [[nodiscard]] bool is_set() const { return met_.load(std::memory_order_relaxed); }

 private:
  std::atomic<bool> met_{false};
};

struct ImpactLane {
  ScratchVector<DiscEvent> heap;    ///< the event queue (later_event: a heap)
  std::vector<DiscImpact> log;      ///< the impacts resolved, in the order resolved
  std::vector<ExtraPair> extra;     ///< reach()'s extra pairs, linked per disc
  std::vector<GrownBox> grown;      ///< the discs whose boxes grew, with the box as paired
  GrownGrid grid;                   ///< the bands the boxes grew by
  std::vector<std::uint32_t> held;  ///< the discs held in the tick
  std::uint32_t mark = 0;           ///< reach()'s last partner mark
  EventBudget budget;
  // One of two lanes (disc_lanes.cpp) only:
  bool split = false;            ///< true: it stops where the other lane could matter
  std::uint8_t id = 0;           ///< 0 or 1
  bool met = false;              ///< it stopped: the tick's impacts run again in one lane
  std::uint32_t next_extra = 0;  ///< its extra pairs' slots: base + 2 i + id, i counted
  ContactStats stats;            ///< its impacts, wall impacts (the rest unused)
  std::vector<std::pair<std::uint32_t, SweptBox>> bands;  ///< each band it grew, with its disc

  [[nodiscard]] std::size_t bytes() const {
    return copy_bytes(heap, log, extra, grown, held, bands) + grid.bytes();
  }
};

}  // namespace fixstep::detail
