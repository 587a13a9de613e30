// A program's per-tick rules (a game's logic), in a form replay() and SyncTest can run, so a
// game with rules records, replays and sync-tests through the library instead of copying the
// loop by hand.
#pragma once

#include <any>
#include <functional>

#include "fixstep/core/input.hpp"
#include "fixstep/core/world.hpp"

namespace fixstep {

/// What a program runs right after (or before) every tick: score a hit, cut a rope, spawn or
/// destroy a body. A run with rules is "before_tick(sim, input), step(input), then
/// after_tick(sim, input)" for every tick (TickRules::tick), live, in replay() and in SyncTest
/// alike, so the state hashes a recording stores (taken after the
/// rules) come back on replay.
///
/// Rules that remember something between ticks outside the world (a score, a phase) give
/// save and restore, so a rollback (SyncTest) puts their state back with the world's; rules
/// whose state is all in the world leave both empty. stateful_rules() makes all three from a
/// copyable state.
struct TickRules {
  /// Called right after sim.step(input). May change the world through World's handle
  /// API; must depend only on the world, the input and the rules' own state (determinism).
  std::function<void(World& sim, const TickInput& input)> after_tick;
  /// The rules' state now (an opaque copy); empty for rules without state.
  std::function<std::any()> save;
  /// Puts back a state save() returned.
  std::function<void(const std::any& state)> restore;
  /// Called right before sim.step(input) (input → rules → step: what a key sets in the rules
  /// acts in the same tick), under the same terms as after_tick. A program may give either or
  /// both.
  std::function<void(World& sim, const TickInput& input)> before_tick;
  /// Called once with every World these rules are about to step, before its first tick (by
  /// replay(), SyncTest, diff_recordings and a network match's worlds): what the world needs
  /// of the program that is not state, its pre-solve hook (World::set_pre_solve).
  std::function<void(World& sim)> attach;

  /// Whether there is anything to run.
  explicit operator bool() const {
    return static_cast<bool>(after_tick) || static_cast<bool>(before_tick);
  }

  /// One tick with the rules: before_tick, sim.step(input), after_tick (each when given).
  void tick(World& sim, const TickInput& input) const {
    if (before_tick) before_tick(sim, input);
    sim.step(input);
    if (after_tick) after_tick(sim, input);
  }
};

/// Rules kept in `state` (copyable; held by reference, so it must outlive the rules) and run
/// by rule(state, sim, input) after each tick; save and restore copy `state`.
template <class State, class Rule>
[[nodiscard]] TickRules stateful_rules(State& state, Rule rule) {
  return TickRules{[&state, rule](World& sim, const TickInput& input) { rule(state, sim, input); },
                   [&state] { return std::any(state); },
                   [&state](const std::any& saved) { state = std::any_cast<const State&>(saved); },
                   {},
                   {}};
}

}  // namespace fixstep
