// Per-body input in input scripts (`force`, `impulse`, `velocity` in [[at]] tables): what each
// does to its body (Δv = J/m at its tick, a force for its tick only, a kinematic body keeps its
// velocity until changed), the same through `fixstep run --input --record` and back through
// `fixstep replay` bit for bit, and the located error of each bad entry. Runs FIXSTEP_CLI.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fixstep/core/components.hpp>
#include <fixstep/core/input.hpp>
#include <fixstep/core/recording.hpp>
#include <fixstep/scene/input_script.hpp>
#include <fixstep/scene/scene.hpp>
#include <fstream>
#include <iterator>
#include <string>

#include "cli_run.hpp"
#include "fixstep/io/recording_file.hpp"
#include "fixstep/io/summary.hpp"

namespace fixstep {
namespace {

namespace fs = std::filesystem;

// No gravity, no contacts: each body moves only by its input. dt = 0.01 s.
constexpr const char* scene_text = R"([world]
dt = 0.01
integrator = "semi_implicit_euler"

[[body]]
name = "ball"
mass = 2.0
position = [0.0, 0.0]

[[body]]
name = "ship"
mass = 4.0
position = [5.0, 0.0]

[[body]]
name = "paddle"
type = "kinematic"
position = [-5.0, 0.0]

[[body]]
name = "wall"
type = "static"
position = [10.0, 10.0]
)";

// All three keys at tick 10 (force as an array of two), the paddle turned at tick 30.
constexpr const char* script_text = R"([[at]]
tick = 10
impulse = { body = "ball", value = [1.0, 0.5] }
velocity = { body = "paddle", value = [2.0, 0.0] }
force = [{ body = "ship", value = [0.0, 40.0] }, { body = "ship", value = [4.0, 0.0] }]
[[at]]
tick = 30
velocity = { body = "paddle", value = [0.0, -1.0] }
)";

constexpr std::uint64_t ticks = 50;
constexpr double dt = 0.01;

struct ScriptRun {
  World sim;
  std::vector<Body> before, after;  // each body before and after tick 10 (10, 11 ticks run)
};

ScriptRun run_script() {
  const Scene scene = parse_scene(scene_text, "bodies.toml");
  const InputScript script = parse_input_script(script_text, "s.toml", scene.def.bodies);
  EXPECT_TRUE(script.warnings.empty());
  ScriptRun r{World(scene.def), {}, {}};
  for (const TickInput& in : script_inputs(script, ticks)) {
    r.sim.check_input(in);  // nothing World::step would ignore
    r.sim.step(in);
    for (std::size_t i = 0; i < 4 && (r.sim.tick() == 10 || r.sim.tick() == 11); ++i) {
      (r.sim.tick() == 10 ? r.before : r.after).push_back(r.sim.body(r.sim.defined_bodies()[i]));
    }
  }
  return r;
}

TEST(ScriptBodyInput, EachKeyActsAsDocumented) {
  const ScriptRun r = run_script();
  const Body ball = r.sim.body(r.sim.defined_bodies()[0]),
             ship = r.sim.body(r.sim.defined_bodies()[1]),
             paddle = r.sim.body(r.sim.defined_bodies()[2]),
             wall = r.sim.body(r.sim.defined_bodies()[3]);
  // Before tick 10 nothing moves.
  ASSERT_EQ(r.before.size(), 4u);
  for (const Body& b : r.before) EXPECT_EQ(b.velocity, (Vec2{0.0, 0.0}));
  // The impulse J = (1, 0.5) N·s on 2 kg: Δv = J/m = (0.5, 0.25) m/s at tick 10, kept after.
  EXPECT_NEAR(r.after[0].velocity.x, 0.5, 1e-15);
  EXPECT_NEAR(r.after[0].velocity.y, 0.25, 1e-15);
  EXPECT_NEAR(ball.velocity.x, 0.5, 1e-15);
  EXPECT_NEAR(ball.velocity.y, 0.25, 1e-15);
  EXPECT_NEAR(ball.position.x, 0.5 * dt * (ticks - 10), 1e-12);  // 40 ticks at 0.5 m/s
  // The forces (4, 40) N on 4 kg for tick 10 only: Δv = F dt / m = (0.01, 0.1) m/s, then no
  // more (a force that stayed on would double it by tick 11).
  EXPECT_NEAR(r.after[1].velocity.x, 0.01, 1e-15);
  EXPECT_NEAR(r.after[1].velocity.y, 0.1, 1e-15);
  EXPECT_NEAR(ship.velocity.x, 0.01, 1e-15);
  EXPECT_NEAR(ship.velocity.y, 0.1, 1e-15);
  EXPECT_NEAR(ship.position.y, 0.1 * dt * (ticks - 10), 1e-12);
  // The paddle: 2 m/s to the right for ticks 10..29, then 1 m/s down for ticks 30..49.
  EXPECT_NEAR(r.after[2].velocity.x, 2.0, 1e-15);
  EXPECT_NEAR(paddle.position.x, -5.0 + 2.0 * dt * 20, 1e-12);
  EXPECT_NEAR(paddle.position.y, -1.0 * dt * 20, 1e-12);
  EXPECT_EQ(paddle.velocity, (Vec2{0.0, -1.0}));
  EXPECT_EQ(wall.position, (Vec2{10.0, 10.0}));
}

using testing::fixstep_cli;
using testing::text_of;

// `fixstep run --input --record` gives the library's state bit for bit (the same state hash),
// the recording carries the per-body inputs, and `fixstep replay` verifies every tick.
TEST(ScriptBodyInput, RunRecordsAndReplaysBitForBit) {
  const fs::path dir = fs::temp_directory_path() / fmt::format("script_bodies_{}", ::getpid());
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "bodies.toml") << scene_text;
  std::ofstream(dir / "s.toml") << script_text;
  const fs::path rec = dir / "s.rec", out = dir / "run.out";
  ASSERT_EQ(fixstep_cli(fmt::format("run '{}' --steps {} --input '{}' --record '{}' --hash-every 1",
                                    (dir / "bodies.toml").string(), ticks,
                                    (dir / "s.toml").string(), rec.string()),
                        out),
            0)
      << text_of(out);
  const ScriptRun r = run_script();
  EXPECT_NE(text_of(out).find("state_hash=" + hex_hash(r.sim.state_hash())), std::string::npos)
      << text_of(out);
  const std::string recorded = text_of(rec);
  EXPECT_NE(recorded.find(
                "tick 10 push=0,0 held=0 pressed=0 released=0 pointer=0,0 drag=none force=2:1,0,40 "
                "force=2:1,4,0 impulse=1:1,1,0.5 velocity=3:1,2,0\n"),
            std::string::npos)
      << recorded;
  const Recording parsed = read_recording(rec);
  EXPECT_EQ(parsed.input_at(10).bodies.size(), 4u);
  EXPECT_TRUE(parsed.input_at(11).bodies.empty());  // events: their tick only
  const fs::path replayed = dir / "replay.out";
  ASSERT_EQ(fixstep_cli(fmt::format("replay '{}'", rec.string()), replayed), 0)
      << text_of(replayed);
  EXPECT_NE(text_of(replayed).find(fmt::format("verified {} hashes", ticks + 1)), std::string::npos)
      << text_of(replayed);
  fs::remove_all(dir);
}

std::string error_of(const std::string& script) {
  const Scene scene = parse_scene(scene_text, "bodies.toml");
  try {
    (void)parse_input_script(script, "s.toml", scene.def.bodies);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(parsed)";
}

TEST(ScriptBodyInput, BadEntriesAreLocatedErrors) {
  const std::string at = "[[at]]\ntick = 3\n";
  EXPECT_EQ(error_of(at + "impulse = { body = \"bal\", value = [1.0, 0.0] }\n"),
            "s.toml:3:20: at[0].impulse.body: no body named \"bal\" (did you mean \"ball\"?)");
  EXPECT_EQ(error_of(at + "velocity = { body = \"ball\", value = [1.0, 0.0] }\n"),
            "s.toml:3:21: at[0].velocity.body: \"ball\" is a dynamic body: velocity is for "
            "kinematic bodies only (push a dynamic one with impulse or force)");
  EXPECT_EQ(error_of(at + "force = { body = \"paddle\", value = [1.0, 0.0] }\n"),
            "s.toml:3:18: at[0].force.body: \"paddle\" is a kinematic body: force acts on "
            "dynamic bodies only (move a kinematic one with velocity)");
  EXPECT_EQ(error_of(at + "impulse = { body = \"wall\", value = [1.0, 0.0] }\n"),
            "s.toml:3:20: at[0].impulse.body: \"wall\" is a static body: impulse acts on dynamic "
            "bodies only");
  EXPECT_EQ(error_of(at + "impulse = { body = \"ball\", value = [nan, 0.0] }\n"),
            "s.toml:3:37: at[0].impulse.value[0]: must be finite (got nan)");
  EXPECT_EQ(error_of(at + "force = { body = \"ball\", value = [1.0] }\n"),
            "s.toml:3:34: at[0].force.value: expected [x, y] (2 numbers), found 1 element");
  EXPECT_EQ(error_of(at + "impulse = { value = [1.0, 0.0] }\n"),
            "s.toml:3:11: at[0].impulse.body: missing (required): the name of the body it acts "
            "on, e.g. body = \"ball\"");
  EXPECT_EQ(
      error_of(at + "impulse = [{ body = \"ball\", value = [1.0, 0.0] }, { body = \"ball\" }]\n"),
      "s.toml:3:51: at[0].impulse[1].value: missing (required): the impulse [x, y] in N*s, "
      "e.g. value = [1.0, 0.5]");
  EXPECT_EQ(error_of(at + "force = [1.0, 2.0]\n"),
            "s.toml:3:10: at[0].force[0]: expected { body = \"NAME\", value = [x, y] } or an "
            "array of them, found a float (1.0)");
  EXPECT_EQ(error_of(at + "velocity = { body = 3, value = [1.0, 0.0] }\n"),
            "s.toml:3:21: at[0].velocity.body: expected a body name (a string), found an integer "
            "(3)");
  // An unknown key inside the table is a warning, as elsewhere in scripts.
  const Scene scene = parse_scene(scene_text, "bodies.toml");
  const InputScript warned = parse_input_script(
      at + "impulse = { body = \"ball\", valu = [1.0, 0.0], value = [1.0, 0.0] }\n", "s.toml",
      scene.def.bodies);
  ASSERT_EQ(warned.warnings.size(), 1u);
  EXPECT_EQ(warned.warnings[0],
            "s.toml:3:28: at[0].impulse.valu: unknown key ignored (did you mean `value`?)");
}

}  // namespace
}  // namespace fixstep
