// Recordings (engine/core/src/recording*.cpp) and input scripts (engine/scene/src/
// input_script.cpp): round trips, replay verification, the first diverging tick, every error
// kind, the Recorder's rewind, and the script's per-tick semantics.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <filesystem>
#include <fixstep/core/components.hpp>
#include <fixstep/core/input.hpp>
#include <fixstep/core/random.hpp>
#include <fixstep/core/recording.hpp>
#include <fixstep/core/world_def.hpp>
#include <fixstep/core/world_settings.hpp>
#include <fixstep/scene/input_script.hpp>
#include <fixstep/scene/scene.hpp>
#include <fstream>
#include <sstream>
#include <string>

#include "fixstep/core/defined_bodies.hpp"
#include "fixstep/io/recording_file.hpp"
#include "link_between.hpp"
#include "text_edit.hpp"

namespace fixstep {
namespace {

WorldDef small_world() {
  WorldDef def;
  def.settings.dt = 0.01;
  BodyDef a, b, c;
  a.name = "a", a.body = {1.0, {1.0, 0.0}, {0.0, 0.5}};
  a.spring = SpringDamper{{0.0, 0.0}, 15.0, 0.1, 0.0};
  b.name = "b", b.body = {2.0, {0.0, 3.0}, {1.0, 0.0}};
  b.gravity = Gravity{};
  b.drag = LinearDrag{0.05};
  c.name = "c", c.body = {0.5, {2.0, 0.0}, {}};
  def.bodies = {a, b, c};
  def.links = {fixstep::test::link_between(0, 2, LinkSpring{20.0, 0.2, 1.0})};
  return def;
}

/// Input of tick t: pushes and buttons that change now and then, a tap at tick 30.
TickInput input_of(std::uint64_t t) {
  TickInput in{.tick = t};
  if (t >= 10 && t < 40) in.push = {3.0, 0.0}, in.held = button_right;
  if (t == 10) in.pressed = button_right;
  if (t == 40) in.released = button_right;
  if (t == 30) in.pressed = in.released = button_action;
  if (t >= 50) in.push = {0.0, -1.25}, in.pointer = {0.5, 0.25};
  return in;
}

Recording record_run(const WorldDef& def, std::uint64_t ticks, std::uint64_t hash_every) {
  World sim = World(def);
  Recorder rec(def, "scenes/small.toml", hash_every);
  for (std::uint64_t t = 0; t < ticks; ++t) {
    sim.step(input_of(t));
    rec.record(input_of(t), sim);
  }
  return rec.finish(sim);
}

RecordingError::Kind parse_kind(const std::string& text) {
  try {
    (void)parse_recording(text, "x.rec");
  } catch (const RecordingError& e) {
    return e.kind();
  }
  ADD_FAILURE() << "parsed:\n" << text;
  return RecordingError::Kind::unreadable;
}

std::string parse_message(const std::string& text) {
  try {
    (void)parse_recording(text, "x.rec");
  } catch (const RecordingError& e) {
    return e.what();
  }
  return "(parsed)";
}

TEST(Recording, EveryTickReadsBackFromTheRunLengthInputs) {
  const Recording rec = record_run(small_world(), 80, 10);
  EXPECT_EQ(rec.ticks, 80u);
  EXPECT_LT(rec.inputs.size(), 12u);  // a line per change, not per tick
  for (std::uint64_t t = 0; t < rec.ticks; ++t) EXPECT_EQ(rec.input_at(t), input_of(t)) << t;
  EXPECT_EQ(rec.hashes.size(), 8u);
  EXPECT_EQ(rec.hashes.front().first, 10u);
}

TEST(Recording, TextAndFileRoundTripsExactly) {
  Recording rec = record_run(small_world(), 80, 7);
  rec.inputs[1].push = {0.1, -1e-300};  // shortest round-trip text must keep every bit
  rec.inputs[2].pointer = {std::nextafter(1.0, 2.0), -0.0};
  rec.inputs[3].drag_body = fixstep::defined_entity(2);
  const std::string text = format_recording(rec);
  EXPECT_EQ(parse_recording(text, "x.rec"), rec);
  EXPECT_EQ(format_recording(parse_recording(text, "x.rec")), text);
  const auto file = std::filesystem::temp_directory_path() /
                    ("fixstep_test_" + std::to_string(::getpid()) + ".rec");
  write_recording(file, rec);
  EXPECT_EQ(read_recording(file), rec);
  std::filesystem::remove(file);
}

TEST(Recording, ReplayVerifiesEveryHash) {
  const WorldDef def = small_world();
  const Recording rec = record_run(def, 100, 10);
  const ReplayReport r = replay(def, rec);
  EXPECT_TRUE(r.ok());
  EXPECT_EQ(r.verified, rec.hashes.size() + 1);  // the final hash too
  EXPECT_EQ(r.ticks, 100u);
  EXPECT_EQ(r.final_hash, rec.final_hash);
}

/// Flips bit `bit` of the push x of the input change in force at tick `tick`, made its own
/// change (so only that tick differs).
Recording flip_push_bit(Recording rec, std::uint64_t tick, int bit) {
  TickInput changed = rec.input_at(tick), after = rec.input_at(tick + 1);
  changed.push.x =
      std::bit_cast<double>(std::bit_cast<std::uint64_t>(changed.push.x) ^ (1ull << bit));
  std::erase_if(rec.inputs,
                [&](const TickInput& in) { return in.tick == tick || in.tick == tick + 1; });
  rec.inputs.push_back(changed);
  rec.inputs.push_back(after);
  std::sort(rec.inputs.begin(), rec.inputs.end(),
            [](const TickInput& a, const TickInput& b) { return a.tick < b.tick; });
  return rec;
}

/// A seeded world recorded for 30 ticks with rules that roll a die each tick (the roll enters
/// the state hash), written and read back.
Recording dice_recording(Seeding seeding) {
  WorldDef def = small_world();
  def.settings.seed = std::uint64_t{1} << 62;
  def.settings.seeding = seeding;
  World sim(def);
  Recorder rec(def, "dice", 1);
  rec.set_rules("dice", 1);
  for (std::uint64_t t = 0; t < 30; ++t) {
    sim.step(input_of(t));
    (void)sim.random().below(6);
    rec.record(input_of(t), sim);
  }
  return parse_recording(format_recording(rec.finish(sim)), "dice.rec");
}

ReplayReport replay_dice(const Recording& rec, std::optional<Seeding> force = {}) {
  WorldDef def = small_world();
  def.settings.seed = std::uint64_t{1} << 62;
  apply_settings(def, rec.settings);  // the recording's seeding (from its version)
  if (force) def.settings.seeding = *force;
  EXPECT_EQ(definition_hash(def) == rec.definition_hash, !force.has_value());
  World sim(def);
  return replay(
      sim, rec,
      TickRules{[](World& w, const TickInput&) { (void)w.random().below(6); }, {}, {}, {}, {}});
}

// A seeded world records as version 5 (SplitMix64 seeding); one of version 4 (the older
// seeding, as assets/recordings/peggle.rec) reads back with that seeding and replays; each
// replayed with the other seeding diverges at its first roll.
TEST(Recording, TheVersionSelectsTheSeedingOfTheWorldsGenerator) {
  const Recording mixed = dice_recording(Seeding::splitmix);
  EXPECT_EQ(mixed.version, 5);
  EXPECT_EQ(mixed.settings.seeding, Seeding::splitmix);
  EXPECT_FALSE(replay_dice(mixed).mismatch);
  EXPECT_EQ(replay_dice(mixed).verified, 31u);
  const Recording older = dice_recording(Seeding::pcg32_srandom);
  EXPECT_EQ(older.version, 4);
  EXPECT_EQ(older.settings.seeding, Seeding::pcg32_srandom);
  EXPECT_EQ(replay_dice(older).verified, 31u);
  ASSERT_TRUE(replay_dice(older, Seeding::splitmix).mismatch);
  EXPECT_EQ(replay_dice(older, Seeding::splitmix).mismatch->tick, 1u);
  ASSERT_TRUE(replay_dice(mixed, Seeding::pcg32_srandom).mismatch);
  // Seed 0: the same generator either way, so its recording keeps version 3 (older builds).
  Recorder unseeded(small_world(), "scenes/small.toml", 10);
  EXPECT_EQ(unseeded.finish(World(small_world())).version, 3);
}

TEST(Recording, OneFlippedInputBitIsReportedAtItsTick) {
  const WorldDef def = small_world();
  for (const std::uint64_t tick : {0u, 17u, 55u, 98u}) {
    const Recording bad = flip_push_bit(record_run(def, 100, 1), tick, 62);
    // Read back from text, as `fixstep replay` does: no checksum refuses the flipped bit.
    const ReplayReport r = replay(def, parse_recording(format_recording(bad), "x.rec"));
    ASSERT_FALSE(r.ok()) << tick;
    EXPECT_EQ(r.mismatch->tick, tick + 1);  // the state after the flipped tick
    EXPECT_EQ(r.mismatch->last_match, tick);
    EXPECT_EQ(r.verified, tick);
    EXPECT_NE(r.mismatch->expected, r.mismatch->actual);
  }
  // With a hash every 10 ticks the difference shows at the next stored hash.
  const ReplayReport r = replay(def, flip_push_bit(record_run(def, 100, 10), 17, 62));
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.mismatch->tick, 20u);
  EXPECT_EQ(r.mismatch->last_match, 10u);
}

TEST(Recording, ASceneThatChangedIsAMismatch) {
  const WorldDef def = small_world();
  const Recording rec = record_run(def, 20, 10);
  WorldDef other = def;
  other.bodies[1].body.mass = std::nextafter(2.0, 3.0);
  try {
    (void)replay(other, rec);
    FAIL() << "replayed on another world";
  } catch (const RecordingError& e) {
    EXPECT_EQ(e.kind(), RecordingError::Kind::scene_mismatch);
    EXPECT_NE(std::string(e.what()).find("definition"), std::string::npos) << e.what();
  }
}

TEST(Recording, DefinitionHashCoversWhatChangesStatesOnly) {
  const WorldDef def = small_world();
  const std::uint64_t h = definition_hash(def);
  WorldDef same = def;
  same.bodies[0].name = "renamed";
  same.bodies[0].appearance = Appearance{};
  same.settings.track_dissipation = !def.settings.track_dissipation;
  EXPECT_EQ(definition_hash(same), h);
  auto changed = [&](auto&& edit) {
    WorldDef d = def;
    edit(d);
    return definition_hash(d) != h;
  };
  EXPECT_TRUE(changed([](WorldDef& d) { d.settings.dt = 0.005; }));
  EXPECT_TRUE(changed([](WorldDef& d) { d.settings.integrator = Integrator::rk4; }));
  EXPECT_TRUE(changed([](WorldDef& d) { d.settings.substeps = 2; }));
  EXPECT_TRUE(changed([](WorldDef& d) { d.precision = Precision::f32; }));
  EXPECT_TRUE(changed([](WorldDef& d) { d.bodies[2].body.velocity.y = -0.0; }));
  EXPECT_TRUE(changed([](WorldDef& d) { d.bodies[1].drag.reset(); }));
  EXPECT_TRUE(changed([](WorldDef& d) { d.bodies[1].drag->coefficient = 0.06; }));
  EXPECT_TRUE(changed([](WorldDef& d) { d.bodies[0].spring->anchor.y = 1e-300; }));
  EXPECT_TRUE(changed([](WorldDef& d) { d.bodies[1].gravity->acceleration.x = 0.5; }));
  EXPECT_TRUE(changed([](WorldDef& d) { d.settings.flush_denormals = false; }));
  EXPECT_TRUE(changed([](WorldDef& d) { d.bodies[2].constant_force = ConstantForce{}; }));
  EXPECT_TRUE(changed([](WorldDef& d) { d.links[0].spring.rest_length = 1.5; }));
  EXPECT_TRUE(changed([](WorldDef& d) { std::swap(d.bodies[0], d.bodies[2]); }));
  EXPECT_TRUE(changed([](WorldDef& d) { d.bodies[1].collider = Collider{.radius = 0.25}; }));
  EXPECT_TRUE(changed([](WorldDef& d) { d.planes.push_back(PlaneDef{}); }));
  WorldDef with_plane = def;
  with_plane.planes.push_back(PlaneDef{.normal = {0, 1}, .offset = -5.0, .restitution = 0.5});
  const std::uint64_t hp = definition_hash(with_plane);
  for (auto edit :
       {+[](PlaneDef& p) { p.normal.x = 0.25; }, +[](PlaneDef& p) { p.offset = -4.0; },
        +[](PlaneDef& p) { p.restitution = 0.75; }, +[](PlaneDef& p) { p.friction = 0.1; }}) {
    WorldDef d = with_plane;
    edit(d.planes[0]);
    EXPECT_NE(definition_hash(d), hp);
  }
}

TEST(Recording, RecorderFollowsTheTimelineKeptAfterARewind) {
  const WorldDef def = small_world();
  World sim = World(def);
  Recorder rec(def, "small.toml", 5);
  WorldSnapshot at20;
  for (std::uint64_t t = 0; t < 50; ++t) {
    if (t == 20) sim.save(at20);
    TickInput in = input_of(t);
    in.push.x += 7.0;  // the abandoned timeline
    sim.step(in);
    rec.record(in, sim);
  }
  EXPECT_THROW(rec.record(input_of(50), sim), std::invalid_argument);  // tick 51 expected
  sim.restore(at20);
  rec.truncate(20);
  EXPECT_THROW(rec.truncate(21), std::invalid_argument);
  for (std::uint64_t t = 20; t < 80; ++t) {
    sim.step(input_of(t));
    rec.record(input_of(t), sim);
  }
  const Recording kept = rec.finish(sim);
  // A straight recording of the timeline that was kept: 20 ticks pushed harder, then input_of.
  World fresh = World(def);
  Recorder straight(def, "small.toml", 5);
  for (std::uint64_t t = 0; t < 80; ++t) {
    TickInput in = input_of(t);
    if (t < 20) in.push.x += 7.0;
    fresh.step(in);
    straight.record(in, fresh);
  }
  EXPECT_EQ(kept, straight.finish(fresh));
  EXPECT_EQ(kept.ticks, 80u);
  EXPECT_EQ(kept.hashes.size(), 16u);
  EXPECT_TRUE(replay(def, kept).ok());
  for (std::uint64_t t = 20; t < 80; ++t) EXPECT_EQ(kept.input_at(t), input_of(t));
}

TEST(Recording, EveryCutShortFileIsTruncated) {
  const std::string text = format_recording(record_run(small_world(), 60, 10));
  for (std::size_t n = 0; n < text.size(); ++n) {
    EXPECT_EQ(parse_kind(text.substr(0, n)), RecordingError::Kind::truncated) << n;
  }
  EXPECT_NE(parse_message(text.substr(0, text.size() - 30)).find("x.rec:"), std::string::npos);
}

using testing::replaced;

TEST(Recording, ForeignVersionAndCorruptFilesAreEachTheirKind) {
  using K = RecordingError::Kind;
  const std::string text = format_recording(record_run(small_world(), 60, 10));
  EXPECT_EQ(parse_kind("[world]\ndt = 0.01\n"), K::foreign);
  const std::string magic = "fixstep-recording " + std::to_string(recording_version_without_rules);
  EXPECT_EQ(parse_kind(replaced(text, magic,
                                "fixstep-recording " + std::to_string(recording_version + 1))),
            K::unsupported_version);
  EXPECT_EQ(parse_kind(replaced(text, magic, "fixstep-recording x")), K::corrupt);
  const std::pair<std::string, std::string> corrupt[] = {
      {"held=2 ", "held=400 "},    // a bit outside all_buttons
      {"push=3,0", "push=inf,0"},  // not finite
      {"push=3,0", "push=3;0"},    // not X,Y
      {"tick 10 ", "tick 0 "},     // out of order
      {"hash 20 ", "hash 99 "},    // beyond the end (60 ticks)
      {"end 60 ", "end 60  "},     // two spaces
      {"dt 0.01", "dt 0"},         // out of range
      {"integrator semi_implicit_euler", "integrator leapfrog"},
      {"damping_split per_stage", "damping_split per_tick"},
      {"drag=none", "drag=-1"},
      {"end 60 ", "end 1000000001 "},  // beyond max_recording_ticks
  };
  for (const auto& [from, to] : corrupt) {
    EXPECT_EQ(parse_kind(replaced(text, from, to)), K::corrupt) << to;
  }
  EXPECT_EQ(parse_kind(text + "tick 70 push=0,0\n"), K::corrupt);  // text after `end`
  // A control character in the scene path (fuzz_recording's first finding: it read, then
  // could not be written back).
  EXPECT_EQ(parse_kind(replaced(text, "scenes/small", std::string("scenes\0small", 12))),
            K::corrupt);
  EXPECT_EQ(parse_kind(replaced(text, "scenes/small", "scenes\tsmall")), K::corrupt);
  const std::string message = parse_message(replaced(text, "held=2 ", "held=400 "));
  EXPECT_NE(message.find("x.rec:12: held: bits 400 are not buttons"), std::string::npos) << message;
}

TEST(Recording, MissingFileAndDirectoryAreUnreadable) {
  const std::pair<const char*, const char*> cases[] = {
      {"/nonexistent/x.rec",
       "/nonexistent/x.rec: no such recording: the directory /nonexistent "
       "does not exist"},
      {"/", "/: is a directory, not a recording"},
      {FIXSTEP_SOURCE_DIR "/no_such.rec", FIXSTEP_SOURCE_DIR "/no_such.rec: no such recording"}};
  for (const auto& [path, message] : cases) {
    try {
      (void)read_recording(path);
      FAIL() << path;
    } catch (const RecordingError& e) {
      EXPECT_EQ(e.kind(), RecordingError::Kind::unreadable) << e.what();
      EXPECT_EQ(std::string(e.what()), message);
    }
  }
}

TEST(Recording, AnEmptyFileOrASceneIsNamedForWhatItIs) {
  EXPECT_EQ(parse_message(""),
            "x.rec: empty file, not a recording (`fixstep run SCENE --steps N --record FILE` "
            "writes one)");
  EXPECT_EQ(parse_message("[world]\ndt = 0.01\n"),
            "x.rec:1: not a fixstep recording: the first line is \"[world]\", a recording's is "
            "`fixstep-recording 3` (this looks like a TOML scene: replay takes a recording made "
            "by `fixstep run SCENE --steps N --record FILE`)");
  EXPECT_EQ(parse_message("hello\n"),
            "x.rec:1: not a fixstep recording: the first line is \"hello\", a recording's is "
            "`fixstep-recording 3`");
}

TEST(Recording, TheFuzzCorpusIsValid) {
  const auto dir = std::filesystem::path(FIXSTEP_SOURCE_DIR) / "tests/fuzz/recording_corpus";
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const Recording rec = read_recording(entry.path());
    // format_recording writes recording_version_of(rec) (3 without rules, 4 with, 5 for a
    // seeded world of the mixed seeding): an older
    // recording comes back the same but for its version.
    Recording again = parse_recording(format_recording(rec), "again");
    EXPECT_EQ(again.version, recording_version_of(rec));
    again.version = rec.version;
    EXPECT_EQ(again, rec) << entry.path();
    ++files;
  }
  EXPECT_GE(files, 1);
}

// --- input scripts -----------------------------------------------------------------------

TEST(InputScript, LevelsPersistAndEdgesReachExactlyTheirTick) {
  const WorldDef def = small_world();
  const InputScript script = parse_input_script(R"(
[[at]]
tick = 2
press = ["left", "pointer_primary"]
push = [1.5, 0.0]
pointer = [0.5, -1.0]
drag = "c"
[[at]]
tick = 5
release = ["left"]
drag = false
)",
                                                "s.toml", def.bodies);
  const std::vector<TickInput> in = script_inputs(script, 8);
  ASSERT_EQ(in.size(), 8u);
  EXPECT_EQ(in[1], TickInput{.tick = 1});
  EXPECT_EQ(in[2].pressed, button_left | button_pointer_primary);
  EXPECT_EQ(in[3].pressed, 0u);
  EXPECT_EQ(in[4].held, button_left | button_pointer_primary);
  EXPECT_EQ(in[4].push, (Vec2{1.5, 0.0}));
  EXPECT_EQ(in[4].pointer, (Vec2{0.5, -1.0}));
  EXPECT_EQ(in[4].drag_body, fixstep::defined_entity(2));
  EXPECT_EQ(in[5].released, button_left);
  EXPECT_EQ(in[5].held, button_pointer_primary);
  EXPECT_EQ(in[5].drag_body, null_entity);
  EXPECT_EQ(in[6].released, 0u);
  EXPECT_EQ(in[7].push, (Vec2{1.5, 0.0}));
  for (std::uint64_t t = 0; t < 8; ++t) EXPECT_EQ(in[t].tick, t);
}

std::string script_error(const std::string& text) {
  try {
    (void)parse_input_script(text, "s.toml", small_world().bodies);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(parsed)";
}

TEST(InputScript, ErrorsNameFileLineAndKey) {
  EXPECT_EQ(script_error("[[at]]\ntick = 1\npress = [\"lft\"]\n"),
            "s.toml:3:10: at[0].press[0]: unknown action \"lft\"; did you mean \"left\"? (valid: "
            "left, right, up, down, action, pointer_primary, pointer_secondary)");
  EXPECT_EQ(script_error("[[at]]\ntick = 1\ndrag = \"bb\"\n"),
            "s.toml:3:8: at[0].drag: no body named \"bb\" (did you mean \"b\"?)");
  EXPECT_EQ(script_error("[[at]]\ntick = 4\n[[at]]\ntick = 4\n"),
            "s.toml:4:8: at[1].tick: ticks must increase from one [[at]] to the next (4 after 4)");
  EXPECT_EQ(script_error("[[at]]\npush = [1.0, 0.0]\n"),
            "s.toml:1:1: at[0].tick: missing (required): the tick (0, 1, ...) at which this [[at]] "
            "table's inputs apply, e.g. tick = 0");
  EXPECT_EQ(script_error("[[at]]\ntick = -1\n"),
            "s.toml:2:8: at[0].tick: must be 0 .. 999999999 (got -1)");
  EXPECT_EQ(script_error("[[at]]\ntick = 0\npush = [nan, 0.0]\n"),
            "s.toml:3:9: at[0].push[0]: must be finite (got nan)");
  EXPECT_EQ(script_error("[[at]]\ntick = 0\ndrag = true\n"),
            "s.toml:3:8: at[0].drag: expected a body name or false, found true");
  // A scene given as the script would run with no input: it is refused, naming what a script
  // holds.
  EXPECT_EQ(script_error("[world]\ndt = 0.01\n[[body]]\nmass = 1\nposition = [0, 0]\n"),
            "s.toml:1:1: this is a scene file, not an input script: a script holds [[at]] tables "
            "(tick, press, release, pointer, push, drag, force, impulse, velocity, torque, "
            "angular_impulse, angular_velocity, target_angle); see docs/CLI.md, Input scripts");
  EXPECT_EQ(script_error("[[at]]\ntick = 0\npush = 3.0\n"),
            "s.toml:3:8: at[0].push: expected [x, y], found a float (3.0)");
  const InputScript warned =
      parse_input_script("[[at]]\ntick = 0\npussh = [1.0, 0.0]\n", "s.toml", small_world().bodies);
  ASSERT_EQ(warned.warnings.size(), 1u);
  EXPECT_EQ(warned.warnings[0],
            "s.toml:3:1: at[0].pussh: unknown key ignored (did you mean `push`?)");
}

TEST(InputScript, TheShippedScriptLoadsForTheDefaultScene) {
  const std::string src = FIXSTEP_SOURCE_DIR;
  const Scene scene = load_scene(src + "/assets/scenes/default.toml");
  const InputScript script =
      load_input_script(src + "/assets/inputs/default_push.toml", scene.def.bodies);
  EXPECT_TRUE(script.warnings.empty());
  EXPECT_GE(script.events.size(), 6u);
}

}  // namespace
}  // namespace fixstep
