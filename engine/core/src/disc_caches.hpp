// What DiscContacts keeps beyond a tick's state to save work: the grid of the sleepers where
// they sleep, the discs flipped since the awake list was made, and the fat boxes with their
// pairs (disc_live.cpp, disc_fat.cpp). The grids are caches a copy (a snapshot) does not take:
// a copy builds its own when it first needs them, and makes its awake list from every disc.
#pragma once

#include <cstdint>
#include <vector>

#include "fat_boxes.hpp"
#include "grid_broadphase.hpp"
#include "query_grid.hpp"

namespace fixstep::detail {

/// The sleepers where they sleep (for_each_sleeper_near()): a cache, which a copy (a
/// snapshot) does not take; it builds its own when first asked. It is kept across changes of
/// sleep: an entry whose disc woke since is skipped, and a disc that fell asleep since is an
/// extra, tested alone by every query, until the grid is built again: once the extras' tests
/// since the last build cost more than a build (a ski rental: never more than twice the work
/// of the better choice made in hindsight), or a quarter of the entries are gone.
struct SleeperGrid {
  QueryGrid grid;
  std::vector<std::uint32_t> disc;  ///< the grid's disc i is disc disc[i]
  /// Per disc: 1 while its entry is where it sleeps (asleep since the grid was built); 1 while
  /// it is in `extras`.
  std::vector<std::uint8_t> indexed, extra;
  /// The discs that fell asleep since the grid was built (some may have woken again since).
  std::vector<std::uint32_t> extras;
  std::size_t gone = 0;    ///< entries whose disc woke since the grid was built
  std::size_t tested = 0;  ///< the extras' tests since the grid was built
  /// A build's work per entry, in box tests of an extra (it hashes, counts and sorts it).
  static constexpr std::size_t build_tests = 8;

  /// Disc k fell asleep.
  void fell_asleep(std::uint32_t k) {
    if (grid.stale || extra[k] != 0) return;
    extra[k] = 1, extras.push_back(k);
  }
  /// Disc k woke.
  void woke(std::uint32_t k) {
    if (grid.stale || indexed[k] == 0) return;
    indexed[k] = 0, ++gone;
  }
  /// Whether the grid is to be built (again) before the next query.
  [[nodiscard]] bool spent() const {
    return grid.stale || tested > build_tests * (disc.size() + 8) || gone * 4 > disc.size();
  }

  SleeperGrid() = default;
  SleeperGrid(const SleeperGrid& /*other*/) {}
  SleeperGrid& operator=(const SleeperGrid& /*other*/) {
    grid.stale = true;
    return *this;
  }
  ~SleeperGrid() = default;
};

/// The discs that fell asleep or woke since DiscContacts::awake() made its list, by which it
/// updates the list, unless `whole`: after a rebuild, once the flips pass a quarter of the
/// discs (a merge would then cost what a pass over every disc does), and in a copy (a
/// snapshot), which so makes its next list from every disc: a reference for the lean update.
struct AwakeFlips {
  std::vector<std::uint32_t> discs, scratch;
  bool whole = true;
  AwakeFlips() = default;
  AwakeFlips(const AwakeFlips& /*other*/) {}
  AwakeFlips& operator=(const AwakeFlips& /*other*/) {
    discs.clear(), whole = true;
    return *this;
  }
  AwakeFlips(AwakeFlips&&) noexcept = default;
  AwakeFlips& operator=(AwakeFlips&&) noexcept = default;
  ~AwakeFlips() = default;
  /// Disc k fell asleep or woke (n: the discs).
  void flip(std::uint32_t k, std::size_t n) {
    if (whole) return;
    if (discs.size() * 4 >= n) {
      whole = true, discs.clear();
      return;
    }
    discs.push_back(k);
  }
};

/// Whether the broadphase's grid holds fat_.boxes (reach() queries it): false in a copy,
/// whose broadphase keeps its own scratch.
struct FatGridHeld {
  bool value = false;
  FatGridHeld() = default;
  FatGridHeld(const FatGridHeld& /*other*/) {}
  FatGridHeld& operator=(const FatGridHeld& /*other*/) {
    value = false;
    return *this;
  }
  ~FatGridHeld() = default;
};

}  // namespace fixstep::detail
