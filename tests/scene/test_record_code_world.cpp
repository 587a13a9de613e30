// A world built in code, recorded with per-tick input and its scene written beside the recording
// (write_scene_beside), or carried in the recording (format_scene as its scene text): the fixstep
// program replays and renders it from the recording alone, and refuses it once a scene beside
// it no longer matches. Runs the program FIXSTEP_CLI.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "cli_run.hpp"
#include "fixstep/core/components.hpp"
#include "fixstep/core/defined_bodies.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/recording.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "fixstep/io/recording_file.hpp"
#include "fixstep/io/summary.hpp"
#include "fixstep/scene/scene_writer.hpp"
#include "link_between.hpp"

namespace fixstep {
namespace {

namespace fs = std::filesystem;

/// A ball falling onto a ground plane, a bob on a link to a static hook, a kinematic paddle,
/// disc contacts on.
WorldDef code_world() {
  WorldDef def;
  def.settings.dt = 1.0 / 120.0;
  def.settings.integrator = Integrator::velocity_verlet;
  def.settings.contacts = ContactSettings{.restitution = 0.5, .friction = 0.2};
  BodyDef ball;
  ball.name = "ball";
  ball.body = Body{.mass = 0.3, .position = {0.1, 2.0}, .velocity = {1.0 / 3.0, 0.0}};
  ball.gravity = Gravity{};
  ball.drag = LinearDrag{0.01};
  ball.collider = Collider{.radius = 0.2, .restitution = 0.8};
  ball.appearance = Appearance{.radius = 0.2, .color = {76, 175, 240, 255}};
  BodyDef hook;
  hook.name = "hook";
  hook.type = BodyType::static_body;
  hook.body.position = {-2.0, 3.0};
  BodyDef bob;  // unnamed: written as body2
  bob.body = Body{.mass = 1.0, .position = {-1.0, 3.0}};
  bob.gravity = Gravity{};
  bob.appearance = Appearance{.radius = 0.35, .color = {230, 87, 46, 255}};
  BodyDef paddle;
  paddle.name = "paddle";
  paddle.type = BodyType::kinematic;
  paddle.body.position = {2.0, 0.5};
  paddle.body.velocity = {-0.5, 0.0};
  paddle.collider = Collider{.radius = 0.4};
  def.bodies = {ball, hook, bob, paddle};
  def.links = {fixstep::test::link_between(
      2, 1, LinkSpring{.stiffness = 200.0, .damping = 0.5, .rest_length = 1.0})};
  def.planes = {PlaneDef{.normal = {0.0, 1.0}, .offset = 0.0, .restitution = 0.6}};
  return def;
}

using testing::fixstep_cli;
using testing::text_of;

TEST(RecordCodeWorld, FixstepReplaysAndRendersItFromTheRecording) {
  const fs::path dir = fs::temp_directory_path() / fmt::format("code_world_{}", ::getpid());
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path rec_file = dir / "session.rec";

  const WorldDef def = code_world();
  const std::string scene = write_scene_beside(rec_file, def);
  EXPECT_EQ(scene, "session.scene.toml");
  World sim = World(def);
  Recorder recorder(def, scene, 1);
  for (std::uint64_t t = 0; t < 150; ++t) {
    TickInput in{.tick = t};
    in.push = {t < 40 ? 3.0 : 0.0, t % 25 < 5 ? 1.5 : 0.0};  // changes every few ticks
    in.pointer = {0.01 * double(t), 2.5};
    in.drag_body = t >= 60 && t < 90 ? fixstep::defined_entity(2)
                                     : null_entity;  // the bob, dragged for half a second
    in.held = t >= 60 && t < 90 ? std::uint32_t{button_pointer_primary} : 0u;
    sim.step(in);
    recorder.record(in, sim);
  }
  write_recording(rec_file, recorder.finish(sim));

  // Run from another directory: the scene is found beside the recording.
  const fs::path out = dir / "replay.out";
  ASSERT_EQ(fixstep_cli(fmt::format("replay '{}'", rec_file.string()), out), 0) << text_of(out);
  EXPECT_NE(text_of(out).find("verified 151 hashes, ticks=150"), std::string::npos) << text_of(out);

  const fs::path frames = dir / "frames";
  const fs::path render_out = dir / "render.out";
  ASSERT_EQ(fixstep_cli(fmt::format("render --replay '{}' --out '{}' --frames 3 --size 64x36",
                                    rec_file.string(), frames.string()),
                        render_out),
            0)
      << text_of(render_out);
  EXPECT_TRUE(fs::exists(frames / "frame_000002.png"));

  // A scene that no longer matches the recording is refused (exit 6).
  std::string text = text_of(dir / scene);
  const std::size_t at = text.find("mass = 0.3\n");
  ASSERT_NE(at, std::string::npos) << text;
  text.replace(at, 10, "mass = 0.30000000000000004");
  std::ofstream(dir / scene) << text;
  EXPECT_EQ(fixstep_cli(fmt::format("replay '{}'", rec_file.string()), out), 6) << text_of(out);
  fs::remove_all(dir);
}

TEST(RecordCodeWorld, ARecordingCarryingFormatSceneReplaysWithNoSceneFile) {
  // A world built in code carried in the recording itself (format_scene's exact form): the
  // fixstep program replays and renders it with no scene file anywhere.
  const fs::path dir = fs::temp_directory_path() / fmt::format("code_world_text_{}", ::getpid());
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path rec_file = dir / "session.rec";
  const WorldDef def = code_world();
  World sim = World(def);
  Recorder recorder(def, "code_world (built in code)", 1, format_scene(def));
  for (std::uint64_t t = 0; t < 60; ++t) {
    TickInput in{.tick = t};
    in.push = {t < 20 ? 2.0 : 0.0, 0.0};
    sim.step(in);
    recorder.record(in, sim);
  }
  write_recording(rec_file, recorder.finish(sim));
  EXPECT_EQ(fs::directory_iterator(dir)->path(), rec_file);  // the recording alone

  const fs::path out = dir / "replay.out";
  ASSERT_EQ(fixstep_cli(fmt::format("replay '{}'", rec_file.string()), out), 0) << text_of(out);
  EXPECT_NE(
      text_of(out).find("verified 61 hashes, ticks=60 state_hash=" + hex_hash(sim.state_hash())),
      std::string::npos)
      << text_of(out);
  const fs::path frames = dir / "frames";
  ASSERT_EQ(fixstep_cli(fmt::format("render --replay '{}' --out '{}' --frames 3 --size 64x36",
                                    rec_file.string(), frames.string()),
                        out),
            0)
      << text_of(out);
  EXPECT_TRUE(fs::exists(frames / "frame_000002.png"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace fixstep
