// Rewinding time: a ring of the world's recent states, one per tick, so a window can step
// back through them (hold a key) and resume from any of them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "fixstep/core/world.hpp"

namespace fixstep {

/// How many ticks a RewindBuffer should keep to span `seconds` (s) of ticks of `dt` (s) within
/// `max_bytes` of states of `state_bytes` each (World::snapshot_bytes()): the smaller of
/// ceil(seconds / dt) and max_bytes / state_bytes, and at least 1. Throws
/// std::invalid_argument unless seconds >= 0 and dt > 0 are finite.
[[nodiscard]] std::size_t rewind_capacity(double seconds, double dt, std::size_t state_bytes,
                                          std::size_t max_bytes);

class RewindBuffer {
 public:
  /// Keeps the states of the last `capacity` ticks (>= 1, else std::invalid_argument).
  /// Memory: capacity snapshots of the world (each World::snapshot_bytes(); choose the
  /// capacity with rewind_capacity() to stay within a budget); slots are allocated when first
  /// filled and reused after that, so push() allocates nothing once the ring has gone round.
  explicit RewindBuffer(std::size_t capacity);

  /// Saves sim's current state as the newest; the oldest is dropped when the ring is full.
  void push(const World& sim);
  /// One tick back: drops the newest state and returns the one before it, to restore
  /// (World::restore, Session::restore); nullptr, dropping nothing, when fewer than two
  /// states are kept. The pointer is valid until the next push().
  [[nodiscard]] const WorldSnapshot* step_back();
  /// Forgets every state (after a restart).
  void clear() { size_ = 0; }
  [[nodiscard]] std::size_t size() const { return size_; }  ///< states kept
  [[nodiscard]] std::size_t capacity() const { return slots_.size(); }
  /// Tick of the oldest state kept (how far back a rewind can go); 0 when empty.
  [[nodiscard]] std::uint64_t oldest_tick() const;

 private:
  std::vector<WorldSnapshot> slots_;
  std::size_t newest_ = 0;  ///< slot of the newest state
  std::size_t size_ = 0;
};

}  // namespace fixstep
