// A world's state as World::state_hash() covers it, field by field (state_fields), and the first
// field where two such states differ (first_difference): what names the body behind two unequal
// state hashes, as two networked peers or two recordings have them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "fixstep/core/types.hpp"
#include "fixstep/core/world.hpp"

namespace fixstep {

/// One body's share of World::state_hash(): exactly the values it mixes in, for one body. A
/// plain fixed-size struct (doubles and fixed-width integers only), so arrays of it can be sent
/// or stored as they are. In an f32 world each value is the float converted to double (exact:
/// equal doubles mean equal floats).
struct BodyState {
  double x = 0.0, y = 0.0;    ///< position, m
  double vx = 0.0, vy = 0.0;  ///< velocity, m/s
  /// Orientation θ, rad, and angular velocity ω, rad/s: 0 in a world without rolling discs
  /// (ContactSettings::rolling), where the hash does not cover them.
  double theta = 0.0, omega = 0.0;
  /// Ticks the body has spent below the sleep speed, and its island's number while asleep (0
  /// awake): 0 in a world without sleeping (ContactSettings::sleep).
  std::uint32_t sleep_ticks = 0, island = 0;
};

/// A world's whole state_hash() input at one tick: every body in bodies() order, which optional
/// parts the hash covers, and random()'s state once drawn from.
struct StateFields {
  std::uint64_t tick = 0;  ///< World::tick()
  Precision precision = Precision::f64;
  std::vector<BodyState> bodies;  ///< in bodies() order
  bool rolling = false;           ///< θ and ω are covered (ContactSettings::rolling)
  bool sleep = false;             ///< sleep_ticks and island are covered (ContactSettings::sleep)
  /// random()'s 64-bit state once it has been drawn from (World::random: the hash covers it
  /// then); nullopt before the first draw.
  std::optional<std::uint64_t> random_state;
};

/// The fields of `world`'s state that state_hash() covers, in its order. Equal StateFields (by
/// first_difference) mean equal state hashes and bit-identical states. Allocates the bodies'
/// array; O(bodies). Never throws but std::bad_alloc.
[[nodiscard]] StateFields state_fields(const World& world);

/// World::state_hash() computed from `fields` alone: equal to the hash of the world they were
/// read from (state_fields), so a peer can check a state it was sent against a hash. Never
/// throws.
[[nodiscard]] std::uint64_t state_hash(const StateFields& fields);

/// StateDifference::body of a difference that is not one body's (the body count, the random
/// generator).
inline constexpr std::size_t no_body = static_cast<std::size_t>(-1);

/// The first field where two states differ.
struct StateDifference {
  std::uint64_t tick = 0;  ///< the states' tick (ours)
  /// Index in bodies() order (of both states), or no_body for "bodies" and "random".
  std::size_t body = no_body;
  /// "x", "y", "vx", "vy", "theta", "omega", "sleep_ticks", "island" (a body's); "bodies" (the
  /// body counts differ: ours and theirs are the counts); "rolling" or "sleep" (one state covers
  /// those fields and the other does not: 1 or 0); "random" (the generators' states: ours and
  /// theirs are their low 53 bits, bits_ours and bits_theirs the whole states; a state not yet
  /// drawn from reads as 0 with drawn_ours / drawn_theirs false).
  std::string field;
  double ours = 0.0, theirs = 0.0;  ///< the values, in the field's unit (see unit_of)
  /// The values' exact bits: a double's (an f32 world's float's when `f32`), a counter's value,
  /// the generator's state.
  std::uint64_t bits_ours = 0, bits_theirs = 0;
  bool f32 = false;  ///< the world steps in f32: bits are the floats' (32 bits)
  bool drawn_ours = true, drawn_theirs = true;  ///< for "random": drawn from yet
};

/// The unit of a StateDifference field: "m", "m/s", "rad", "rad/s", "ticks", or "" (a count,
/// an island's number, a generator's state, a flag).
[[nodiscard]] const char* unit_of(const std::string& field);

/// The first difference between two states, comparing bit patterns (0.0 and -0.0 differ, and
/// so do NaNs of different payloads): the body counts first, then which parts are covered, then
/// body by body in order, each body's fields in the hash's order (x, y, vx, vy, theta, omega,
/// sleep_ticks, island; the last four only where covered), then random()'s state. nullopt when
/// the states hash alike field for field. The precisions are not compared (a state's values are
/// its world's). Never throws but std::bad_alloc.
[[nodiscard]] std::optional<StateDifference> first_difference(const StateFields& ours,
                                                              const StateFields& theirs);

/// One line naming the difference: `body 12 ("puck") vx: 1.25 against 1.2500000000000002 m/s
/// (bits 0x3ff4000000000000 against 0x3ff4000000000001) at tick 31`. Values in shortest
/// round-trip decimals; the body's name is read from `names` (its bodies() order must be the
/// states': the world of either side at that tick) when given and the body has one.
[[nodiscard]] std::string describe(const StateDifference& difference, const World* names = nullptr);

}  // namespace fixstep
