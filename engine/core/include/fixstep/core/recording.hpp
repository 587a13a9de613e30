// Recordings: every tick's input of a session plus state hashes along the way, replayed headless
// to verify, bit for bit, that the engine still computes the same states. Their text and files
// are fixstep::io's (recording_file.hpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "fixstep/core/input.hpp"
#include "fixstep/core/integrators.hpp"
#include "fixstep/core/rules.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"

namespace fixstep {

/// The newest format version this build reads and writes. Version 5: the world's random
/// generator is seeded through SplitMix64 (Seeding::splitmix); a recording of an older version
/// replays with the seeding it was made with (Seeding::pcg32_srandom: RecordedSettings::seeding).
/// Version 4 names the rules a recording needs (Recording::rules_name). Version 3 may carry the
/// scene the world was loaded from (Recording::scene_text); versions 1 and 2 still read.
inline constexpr int recording_version = 5;
/// The version a recording with rules and Seeding::pcg32_srandom is written as.
inline constexpr int recording_version_with_rules = 4;
/// The version a recording without rules and with Seeding::pcg32_srandom is written as (older
/// builds read it).
inline constexpr int recording_version_without_rules = 3;
/// Most bytes of a rules name (Recording::rules_name).
inline constexpr std::size_t max_rules_name_bytes = 64;
/// Whether a rules name may hold `c`: an ASCII letter or digit, '.', '_' or '-'.
[[nodiscard]] constexpr bool is_rules_name_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' ||
         c == '_' || c == '-';
}
/// What is wrong with `name` as a rules name ("" when nothing: 1 .. max_rules_name_bytes of
/// characters is_rules_name_char accepts). Never throws.
[[nodiscard]] std::string rules_name_fault(std::string_view name);
/// Most ticks a recording may hold (about 190 days at 60 Hz).
inline constexpr std::uint64_t max_recording_ticks = 1'000'000'000;
/// Most ticks between two state hashes a recording stores: 100 000 ticks,
/// 28 minutes at 60 Hz. It bounds a recording's claimed ticks by its size: at most this many
/// ticks per hash line (about 33 bytes), so a file of a few hundred bytes cannot claim a replay
/// of 10^9 ticks.
inline constexpr std::uint64_t max_hash_every = 100'000;
/// Largest scene a recording embeds (Recording::scene_text), bytes: the scene loader's own
/// limit (max_scene_bytes, scene.hpp), so every embedded scene is one the loader reads.
inline constexpr std::size_t max_recording_scene_bytes = 4u << 20;

/// FNV-1a (64-bit) over the exact bits of everything in `def` that changes the simulated
/// states: precision, dt, integrator, substeps, flush_denormals, and for every body in order
/// its mass, position, velocity and components (spring, constant force, gravity, drag,
/// collider: present or not, and each field), then every link (indices and spring) and every
/// plane (normal, offset, restitution, friction). Left out, because they change
/// no state: body names and appearances (drawing only), track_dissipation and threads (the
/// states are bit-identical either way) and allow_unstable. Two definitions with the same hash
/// step to the same states from the same inputs.
[[nodiscard]] std::uint64_t definition_hash(const WorldDef& def);

/// The settings a recording was made with (a replay applies them to the scene it loads).
struct RecordedSettings {
  Integrator integrator = Integrator::semi_implicit_euler;
  Precision precision = Precision::f64;
  double dt = 0.01;  ///< s, > 0 and <= 1
  int substeps = 1;  ///< 1 .. 1 000 000
  /// Forest-Ruth's damping split (WorldSettings::damping_split); nullopt when not recorded
  /// (versions 1 and 2): the scene's own then applies.
  std::optional<DampingSplit> damping_split;
  /// How the world's generator was seeded (WorldSettings::seeding): not a line of the file but
  /// its version's (splitmix from version 5, pcg32_srandom before). A world of seed 0 records
  /// pcg32_srandom: both seedings give it the same generator, and its recording keeps the
  /// version older builds read.
  Seeding seeding = Seeding::pcg32_srandom;
  friend bool operator==(const RecordedSettings&, const RecordedSettings&) = default;
};

struct Recording;

/// The format version `rec` is written as: recording_version with Seeding::splitmix (a seeded
/// world); with Seeding::pcg32_srandom (seed 0, or a world replaying an older recording) the
/// version that seeding was last written with, 4 with rules and 3 without, which older builds
/// read and which replays with that seeding.
[[nodiscard]] int recording_version_of(const Recording& rec);

/// The settings of `def` a recording stores (damping_split and seeding included).
[[nodiscard]] RecordedSettings recorded_settings(const WorldDef& def);

/// A recorded session: the world it ran (by definition hash and settings, and from version 3
/// the scene text it was built from), every tick's input and the state hashes to verify.
///
/// Deviation from "one input per tick": `inputs` is run-length encoded, as the file is, so a
/// recording's memory grows with the number of input changes, not with its length (a file of
/// a few lines may name 10^9 ticks). inputs[k] is the input of every tick from inputs[k].tick
/// until the next entry's tick (its `tick` field then reads as that tick: see input_at()).
struct Recording {
  /// The format version: recording_version_of(*this) for one recorded or written by this build.
  int version = recording_version_without_rules;
  /// The scene's name: its file's path as given on the command line (or a label such as
  /// "demo (built in code)"). With scene_text present it is a label only, never read.
  std::string scene;
  /// The bytes of the scene the world was loaded from, exactly as read (at most
  /// max_recording_scene_bytes), so that the recording replays without the file and cannot be
  /// broken by editing it; empty when the recording does not carry them (versions 1 and 2, or
  /// a recorder given no text): such a recording is replayed with the scene file it names.
  std::string scene_text;
  /// The game rules the recording needs, named by the program that made it (fixstep::app::run
  /// writes its Settings::name and rules_version): its ticks were stepped with those rules, so
  /// a replay without them diverges. Empty (and rules_version 0) for a recording of physics
  /// alone, which `fixstep replay` replays. A name is 1 .. max_rules_name_bytes of letters,
  /// digits, '.', '_' and '-'; a version is >= 1.
  std::string rules_name;
  std::uint32_t rules_version = 0;
  std::uint64_t definition_hash = 0;
  RecordedSettings settings;
  std::uint64_t hash_every = 60;  ///< ticks between stored hashes, >= 1
  /// Run-length input changes, ticks strictly increasing; inputs[0].tick == 0 when ticks > 0.
  std::vector<TickInput> inputs;
  /// (tick, state hash after that many ticks), ticks strictly increasing, each in 1 .. ticks.
  std::vector<std::pair<std::uint64_t, std::uint64_t>> hashes;
  std::uint64_t ticks = 0;  ///< ticks recorded, <= max_recording_ticks
  std::uint64_t final_hash = 0;

  /// The input of tick `tick` (< ticks; an empty TickInput{tick} otherwise), with its tick
  /// field set to `tick`. O(log changes).
  [[nodiscard]] TickInput input_at(std::uint64_t tick) const;
  friend bool operator==(const Recording&, const Recording&) = default;
};

/// Records a live session tick by tick. Memory grows with input changes and stored hashes
/// only: record() allocates only when the input changes or a hash is due (amortised).
class Recorder {
 public:
  /// Starts an empty recording of the world `def` (its definition hash and settings), named
  /// `scene` in the file, storing the state hash every `hash_every` ticks (>= 1, else
  /// std::invalid_argument; so is a `scene` holding a control character, which
  /// format_recording would refuse at the end). `scene_text`: the bytes of the scene `def` was
  /// loaded from (Recording::scene_text; the caller's to get right: a replay refuses a text
  /// whose world is not `def`), or empty; more than max_recording_scene_bytes is
  /// std::invalid_argument.
  Recorder(const WorldDef& def, std::string scene, std::uint64_t hash_every,
           std::string scene_text = {});

  /// Appends one tick: `input` is what the tick was stepped with (its tick field is ignored),
  /// `after_the_tick` the simulation right after sim.step(input). Throws std::invalid_argument
  /// when after_the_tick.tick() is not ticks() + 1 (a tick skipped or a rewind without
  /// truncate()).
  void record(const TickInput& input, const World& after_the_tick);
  /// Keeps the first `ticks` ticks only (<= ticks(), else std::invalid_argument): after a
  /// rewind to tick `ticks` the recording follows the timeline that was kept.
  void truncate(std::uint64_t ticks);
  /// The recording so far, ended at `sim`'s state (whose tick() must be ticks(), else
  /// std::invalid_argument). The recorder is left empty.
  [[nodiscard]] Recording finish(const World& sim);
  /// The recording so far, ended at its last stored hash, for a session whose current state is
  /// lost (a tick abandoned half-way by StopRequested, stop_request.hpp): the ticks after the
  /// last stored hash are dropped and its hash is the final one; with no hash stored, the
  /// recording ends at tick 0 with `initial_hash` (the simulation's state_hash() before its
  /// first tick). The recorder is left empty.
  [[nodiscard]] Recording finish_at_last_hash(std::uint64_t initial_hash);

  [[nodiscard]] std::uint64_t ticks() const { return rec_.ticks; }
  /// Names the rules the ticks are stepped with (Recording::rules_name, rules_version). Throws
  /// std::invalid_argument for an empty or longer name, a character outside letters, digits,
  /// '.', '_' and '-', or version 0.
  void set_rules(std::string name, std::uint32_t version);

 private:
  Recording take();  ///< the recording, the recorder left empty (finish*)
  Recording rec_;
};

/// What a replay found.
struct ReplayReport {
  std::uint64_t ticks = 0;       ///< ticks replayed (the recording's, or up to the mismatch)
  std::uint64_t verified = 0;    ///< stored hashes that matched, the final one included
  std::uint64_t final_hash = 0;  ///< state hash where the replay stopped
  struct Mismatch {
    std::uint64_t tick = 0;                  ///< first stored hash tick whose state differs
    std::uint64_t last_match = 0;            ///< the last tick whose hash matched (0: the start)
    std::uint64_t expected = 0, actual = 0;  ///< state hashes
  };
  std::optional<Mismatch> mismatch;  ///< nullopt: every hash matched
  [[nodiscard]] bool ok() const { return !mismatch; }
};

/// Steps `sim` (at tick 0) through every recorded input, running `rules` after each tick (as
/// the recorded session did: see TickRules; the rules must start from the state they had at
/// tick 0), and compares each stored hash and the final one; stops at the first that differs.
/// The state first differs in the ticks (last_match, tick]; with hash_every = 1, at exactly
/// `tick`. Throws std::invalid_argument when sim is not at tick 0.
[[nodiscard]] ReplayReport replay(World& sim, const Recording& rec, const TickRules& rules = {});
/// def with the recording's precision, dt, integrator and substeps, and its damping split when
/// recorded.
void apply_settings(WorldDef& def, const RecordedSettings& settings);

}  // namespace fixstep
