// The bodies that move in a world with sleeping islands (ContactSettings::sleep) or static
// bodies, as runs of consecutive dense indices, so that the per-body passes of a tick (the free
// step, the plane pass, the previous positions) visit the awake bodies only, not the sleepers
// nor the static ones: a world asleep costs a tick nothing per body, and a level's static
// bodies none. Internal to the engine: not installed.
//
// A sleeper's position and velocity do not change while it sleeps (its velocity is 0, the
// disc phases see it as a static disc, and every edit or input that would move it wakes it
// first), so skipping it leaves its state exactly as putting it back after the free step did.
// A static body never moves and its velocity is 0 (WorldKernel::create_body, set_body and
// set_velocity keep it so): the same holds for it.
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace fixstep::detail {

/// [begin, end): indices begin, begin + 1, ..., end - 1.
struct IndexRun {
  std::uint32_t begin = 0, end = 0;
};

/// The runs of the indices i < n for which keep(i) holds, in increasing order.
template <class Keep>
void collect_runs(std::size_t n, Keep&& keep, std::vector<IndexRun>& out) {
  out.clear();
  for (std::uint32_t i = 0; i < n; ++i) {
    if (!keep(i)) continue;
    if (!out.empty() && out.back().end == i) {
      ++out.back().end;
    } else {
      out.push_back(IndexRun{i, i + 1});
    }
  }
}

/// The runs of (the indices of `runs`, less `remove`) and `add`, in increasing order, into
/// `out`: O(runs + add + remove). `add` and `remove` are sorted, without repeats, and apart.
inline void update_runs(std::span<const IndexRun> runs, std::span<const std::uint32_t> add,
                        std::span<const std::uint32_t> remove, std::vector<IndexRun>& out) {
  out.clear();
  auto put = [&](IndexRun r) {
    if (r.begin == r.end) return;
    if (!out.empty() && out.back().end >= r.begin) {
      out.back().end = std::max(out.back().end, r.end);
    } else {
      out.push_back(r);
    }
  };
  std::size_t a = 0, x = 0;
  auto put_added_before = [&](std::uint32_t i) {
    for (; a < add.size() && add[a] < i; ++a) put(IndexRun{add[a], add[a] + 1});
  };
  for (const IndexRun& r : runs) {
    std::uint32_t begin = r.begin;
    for (; x < remove.size() && remove[x] < r.end; ++x) {
      if (remove[x] < begin) continue;
      put_added_before(begin);
      put(IndexRun{begin, remove[x]});
      begin = remove[x] + 1;
    }
    put_added_before(begin);
    put(IndexRun{begin, r.end});
  }
  put_added_before(0xffffffffu);
}

/// Calls f(i) for every index of the runs, in increasing order; returns how many.
template <class F>
std::size_t for_each_in_runs(std::span<const IndexRun> runs, F&& f) {
  std::size_t count = 0;
  for (const IndexRun& r : runs) {
    for (std::uint32_t i = r.begin; i < r.end; ++i) f(i);
    count += r.end - r.begin;
  }
  return count;
}

/// How many indices the runs hold.
inline std::size_t count_in_runs(std::span<const IndexRun> runs) {
  std::size_t count = 0;
  for (const IndexRun& r : runs) count += r.end - r.begin;
  return count;
}

/// The awake runs of the bodies (dense order) and of the plane pass's colliders (the indices
/// of WorldKernel::ContactScratch::body), built with the immovable list when the bodies change,
/// and updated from the bodies that fell asleep or woke when an island does.
struct AwakeRuns {
  std::vector<IndexRun> bodies, colliders;
  /// The passes skip the sleepers and the static bodies: sleeping is on or a body is static,
  /// and the world has no links (the fused sweep, or the energy account's pass over the
  /// bodies; the passes of links step every body, and put those back).
  bool on = false;
  /// Every sleeper's previous position and plane motion are those of a body at rest where it
  /// sleeps: a tick has passed over every body since the runs were built. A copy (a snapshot)
  /// is not primed: the plane motions are scratch it does not copy (scratch_vector.hpp), so its
  /// first tick passes over every body again.
  bool primed = false;
  /// The bodies that fell asleep or woke since the runs were built (WorldKernel::flip_sleep),
  /// by which the next build updates them (WorldKernel::rebuild_immovable), unless `whole`:
  /// they are built from every body. Whole after a structural change, in a copy (a snapshot,
  /// which so has what its first build reads from every body: a reference for the lean
  /// update), and when more bodies flipped than there are.
  std::vector<std::uint32_t> flipped;
  bool whole = true;

  AwakeRuns() = default;
  AwakeRuns(const AwakeRuns& o) : bodies(o.bodies), colliders(o.colliders), on(o.on) {}
  AwakeRuns& operator=(const AwakeRuns& o) {
    bodies = o.bodies, colliders = o.colliders, on = o.on, primed = false;
    flipped.clear(), whole = true;
    return *this;
  }
  AwakeRuns(AwakeRuns&&) noexcept = default;
  AwakeRuns& operator=(AwakeRuns&&) noexcept = default;
  ~AwakeRuns() = default;

  /// Whether a pass may visit the awake runs only.
  [[nodiscard]] bool skip() const { return on && primed; }
};

}  // namespace fixstep::detail
