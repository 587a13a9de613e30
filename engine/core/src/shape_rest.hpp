// The bodies a shape world's tick leaves alone: static bodies and sleepers (ContactSettings::
// sleep). Neither moves in a tick (a sleeper is solved as a static body until a moving body
// pairs with it, which wakes it and makes the lists again), so their state, their boxes and
// the grid of their boxes hold from one tick to the next, and the tick's passes visit only the
// live bodies: the awake dynamic ones and the kinematic ones. A resting body's state is the one
// the kernel gives it (WorldKernel::resolve_shapes): its position, zero velocity, its angle, the
// rotations of that angle, and the margin and box of its motion, which is none.
//
// The kernel makes the lists stale whenever a resting body may change. Where one body alone
// changes (it falls asleep or wakes, set_position, set_velocity: ShapeWorld::unsettle_body),
// the next tick gives the live and those bodies their state and moves those between the lists
// (rebuild_flipped), O(live + changed + extras). Otherwise (set_body, the shapes rebuilt; a
// copy, for a snapshot or a rollback, is stale too: ShapeWorld::unsettle) it fills every
// body's state and makes the lists again (rebuild_whole), O(bodies + shapes); the ticks
// between visit O(live bodies + the resting shapes their boxes meet). In a whole rebuild a
// body that rested at the last one and rests again with the same state, bit for bit (Key),
// keeps the rotations, margin and shapes' boxes made then: a body falling asleep or an island
// waking costs the other resting bodies a comparison each, not their geometry again. The grid
// of the resting boxes is kept too (settle_grid): an entry whose shape woke or changed is
// skipped, a shape that came to rest since is tested box by box (an extra), until those
// extras would cost a tick more than indexing the grid again. Rebuilding the shapes, or
// assigning the world from a copy, forgets the keys and the grid (ShapeWorld::reshape, forget).
//
// The broadphase's pairs are the same, in the same order: the pairs of live shapes from the
// grid of their boxes, and each live shape's pairs with resting ones (near: from the resting
// grid, GridBroadphase::query, and the extras, in ascending order whatever the grid's history),
// merged by (a, b). Two resting shapes are never a pair: neither moves
// nor wakes the other (ShapeWorld::never_pair). A sensor is live wherever its body is, so that
// what it senses at rest stays sensed. Below ShapeWorld::min_grid_shapes shapes nothing rests:
// every body is live, as before the lists.
//
// A joint is live where one of its ends is (live_joints): one whose two ends rest, asleep or
// static, would move neither, and its rows, its forest and the account of it are left as its
// last live tick left them (its impulses, for the warm start when its island wakes). Creating
// or destroying a joint rebuilds the shapes, which makes the lists stale.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "grid_broadphase.hpp"

namespace fixstep::detail {

struct ShapeRest {
  ShapeRest() = default;
  /// A copy is stale and holds nothing: its next tick makes its lists (a copy of the grid
  /// has no table either). Assigning keeps the target's storage and makes it stale.
  ShapeRest(const ShapeRest&) {}
  ShapeRest& operator=(const ShapeRest&) {
    stale = true;
    forget();
    return *this;
  }
  ~ShapeRest() = default;

  bool stale = true;
  /// Whether the stale lists are made again from every body (a rebuild, a copy, set_body);
  /// else only the bodies in `flipped` changed, each fallen asleep, woken or with its position
  /// or velocity set (ShapeWorld::unsettle_body, rebuild_flipped).
  bool whole = true;
  std::vector<std::uint32_t> flipped;  ///< bodies_ indices, in the order they flipped
  /// Each kernel body's bodies_ indices, two slots a body (none: fewer), as the last whole
  /// rebuild found them: a flip names a kernel body.
  std::vector<std::uint32_t> of_body;
  std::vector<std::uint32_t> visit;  ///< live and flipped bodies merged (visit_few)
  // Scratch of rebuild_flipped: the bodies that leave the live ones and join them, the shapes
  // that become extras, join the live ones and leave the extras; and of the merges.
  std::vector<std::uint32_t> leave, join, to_extras, join_shapes, from_extras, merged;
  /// Whether resting shapes have their own grid (ShapeWorld::min_grid_shapes shapes or more);
  /// otherwise every body is live.
  bool split = false;
  std::vector<std::uint32_t> live;         ///< bodies the tick visits, ascending
  std::vector<std::uint32_t> live_shapes;  ///< the shapes boxed each tick, ascending
  std::vector<std::uint32_t> statics;      ///< the static bodies, ascending
  std::vector<std::uint32_t> live_joints;  ///< the tick's joints (indices), ascending
  /// The resting shapes, in body order, and 1 for each whose body kept its key (Key: the box
  /// it had at the last rebuild): rebuild_rest fills them, settle_grid reads them.
  std::vector<std::uint32_t> order;
  std::vector<std::uint8_t> order_kept;
  // The grid of the resting shapes' boxes (index() only), kept from one rebuild to the next:
  // `resting[g]` is entry g's shape, `gone[g]` 1 once that shape no longer rests with the box
  // indexed; `slot[k]` shape k's entry while it has rested there since (none otherwise);
  // `extras` the resting shapes the grid does not hold, ascending.
  GridBroadphase grid;
  std::vector<std::uint32_t> resting;
  std::vector<std::uint8_t> gone;
  std::vector<std::uint32_t> slot;
  std::vector<std::uint32_t> extras;
  bool indexed = false;  ///< whether the grid holds a past rebuild's shapes (else made afresh)
  std::size_t gone_count = 0;  ///< entries gone
  static constexpr std::uint32_t none = 0xffffffffu;
  // Scratch: the live shapes' boxes and activity by their place in live_shapes (the
  // broadphase's; rebuild_rest first lends `boxes` the resting shapes' boxes for the grid,
  // which copies them), their pairs in those places, and the live-resting pairs.
  std::vector<SweptBox> boxes;
  std::vector<std::uint8_t> active;
  std::vector<DiscPair> pairs, cross;
  std::vector<std::uint32_t> around;  ///< one live shape's resting neighbours (near)

  /// A body's state as the last rebuild found it resting (start, pose and velocity, each by
  /// its bits), and the tick's dt then: a body that rests again with the same bits still holds
  /// what that rebuild made of it (its rotations, margin and shapes' boxes), which no pass
  /// writes while it rests. `keyed[i]` is 0 for a body that was live or not yet seen.
  struct Key {
    std::array<std::uint64_t, 9> bits{};
    friend bool operator==(const Key& l, const Key& r) {  // (inline: a call to memcmp was not)
      std::uint64_t differ = 0;
      for (std::size_t i = 0; i < l.bits.size(); ++i) differ |= l.bits[i] ^ r.bits[i];
      return differ == 0;
    }
  };
  std::vector<Key> keys;
  std::vector<std::uint8_t> keyed;
  double keyed_dt = 0.0;
  /// Drops every key and the grid: the shapes were rebuilt (their indices, owners and
  /// definitions may have changed), or the world was assigned from a copy.
  void forget() {
    keyed.clear();
    indexed = false;
    whole = true;
  }

  /// Called by rebuild_rest once `order` and `order_kept` are made. Keeps the grid, marking
  /// gone the entries whose shapes no longer rest with their boxes and taking the other
  /// resting shapes as extras; or indexes `order` afresh: where no grid is kept, or where the
  /// extras would cost a tick of `live_shapes` queries more than an index (O(order)), or a
  /// quarter of the entries are gone. `boxes`: every shape's box, by shape index. O(order).
  void settle_grid(std::span<const SweptBox> boxes, std::size_t live_shapes);
  /// Whether the grid holds too many extras or gone entries to keep (settle_grid's rule).
  [[nodiscard]] bool grid_spent(std::size_t live_shapes) const;
  /// Indexes `order` afresh.
  void index_grid(std::span<const SweptBox> boxes);
  /// The resting shapes whose boxes may meet q, ascending, into `out` (cleared first): the
  /// grid's entries not gone (query, then its unindexed ones by their boxes) and the extras.
  void near(const SweptBox& q, std::span<const SweptBox> boxes,
            std::vector<std::uint32_t>& out) const;
};

}  // namespace fixstep::detail
