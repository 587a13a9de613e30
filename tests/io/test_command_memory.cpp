// Every command's memory estimate (cli/command_memory.hpp, fixstep/io/command_limits.hpp):
// refused beyond max_command_bytes before anything is allocated, naming the command, the
// estimate, the bound, the dominant term and the way out; the shipped scenes accepted; and the
// estimate an upper bound of what a world really holds (World::snapshot_bytes) without being
// absurdly above it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fixstep/core/components.hpp>
#include <fixstep/core/limits.hpp>
#include <fixstep/core/world.hpp>
#include <fixstep/core/world_def.hpp>
#include <fixstep/scene/scene.hpp>
#include <string>
#include <vector>

#include "command_memory.hpp"
#include "fixstep/io/command_limits.hpp"

namespace fixstep::cli {
namespace {

/// A scene of `n` bodies in a row (discs of radius 0.05 m 0.1 m apart under [contacts] when
/// `discs`), built in code: the definition alone, no world. Their handles go to `handles`.
Scene row_scene(std::size_t n, bool discs, std::vector<Entity>* handles = nullptr) {
  Scene scene;
  scene.file = "grid.toml";
  if (discs) scene.def.settings.contacts = ContactSettings{};
  scene.def.bodies.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    BodyDef b;
    b.body.mass = 0.01;
    b.body.position = {0.1 * double(i), 0.0};
    if (discs) b.collider = Collider{.radius = 0.05};
    const Entity e = scene.def.add_body(b);
    if (handles) handles->push_back(e);
  }
  return scene;
}

std::string refusal(const std::vector<MemoryTerm>& terms, std::string_view command) {
  try {
    check_memory(command, "grid.toml", terms);
  } catch (const LimitError& e) {
    return e.what();
  }
  return "";
}

TEST(CommandMemoryLimits, RefusesSixTilesOfAMillionBodiesAt8192Squared) {
  const Scene scene = row_scene(1'000'000, false);
  const auto terms = compare_memory(scene, 6, false, 8192, 8192, false);
  EXPECT_GT(total_bytes(terms), max_command_bytes);
  const std::string e = refusal(terms, "compare");
  EXPECT_NE(e.find("compare grid.toml: would need about"), std::string::npos) << e;
  EXPECT_NE(e.find("at most 4 GiB"), std::string::npos) << e;
  EXPECT_NE(e.find("6 tiles (--with) of 1000000 bodies"), std::string::npos) << e;
  EXPECT_NE(e.find("fewer --with tiles"), std::string::npos) << e;
  EXPECT_NE(e.find("--size 8192x8192 frame buffers 2.00 GiB"), std::string::npos) << e;
}

TEST(CommandMemoryLimits, RefusesTheViewOfAMillionTouchingDiscs) {
  const Scene scene = row_scene(1'000'000, true);
  const auto terms = view_memory(scene, 1280, 720);
  EXPECT_GT(total_bytes(terms), max_command_bytes);
  const std::string e = refusal(terms, "view");
  EXPECT_NE(e.find("view grid.toml: would need about"), std::string::npos) << e;
  EXPECT_NE(e.find("[contacts]"), std::string::npos) << e;
  EXPECT_NE(e.find("fewer bodies or links in grid.toml"), std::string::npos) << e;
}

TEST(CommandMemoryLimits, AcceptsTheLargestLinkedGridInViewAndAMillionDiscsInRun) {
  // view_reload_test.sh loads a 1000 x 1000 grid of linked bodies (measured peak 3.2 GB).
  Scene grid = row_scene(1'000'000, false);
  grid.def.links.resize(1'998'000);
  EXPECT_LE(total_bytes(view_memory(grid, 800, 600)), max_command_bytes);
  EXPECT_LE(total_bytes(run_memory(row_scene(1'000'000, true), std::nullopt)), max_command_bytes);
  // The frame alone at its largest, in each command that captures.
  const Scene small = row_scene(10, false);
  EXPECT_LE(total_bytes(render_memory(small, 8192, 8192, false, nullptr)), max_command_bytes);
  // An MP4 or GIF encoder holds more (measured peaks 3.48 and 3.61 GB): still within the bound.
  EXPECT_LE(total_bytes(render_memory(small, 8192, 8192, true, nullptr)), max_command_bytes);
  EXPECT_LE(total_bytes(compare_memory(small, 6, true, 8192, 8192, false)), max_command_bytes);
  EXPECT_LE(total_bytes(compare_memory(small, 6, true, 8192, 8192, true)), max_command_bytes);
}

TEST(CommandMemoryLimits, AcceptsEveryShippedScene) {
  for (const auto& entry : std::filesystem::directory_iterator(
           std::filesystem::path(FIXSTEP_SOURCE_DIR) / "assets/scenes")) {
    if (entry.path().extension() != ".toml") continue;
    const Scene scene = load_scene(entry.path().string());
    SCOPED_TRACE(entry.path().string());
    EXPECT_NO_THROW(check_memory("run", scene.file, run_memory(scene, 10000)));
    EXPECT_NO_THROW(
        check_memory("render", scene.file, render_memory(scene, 1920, 1080, true, nullptr)));
    EXPECT_NO_THROW(
        check_memory("compare", scene.file, compare_memory(scene, 6, true, 1920, 1080, true)));
    EXPECT_NO_THROW(check_memory("view", scene.file, view_memory(scene, 1920, 1080)));
  }
}

TEST(CommandMemoryLimits, TheWorldEstimateBoundsWhatAWorldHolds) {
  for (const bool discs : {false, true}) {
    std::vector<Entity> e;
    Scene scene = row_scene(20'000, discs, &e);
    for (std::size_t i = 0; !discs && i + 1 < e.size(); ++i) {
      scene.def.add_link(e[i], e[i + 1],
                         LinkSpring{.stiffness = 10.0, .damping = 0.1, .rest_length = 0.1});
    }
    World world(scene.def);
    world.step();
    const double held = double(world.snapshot_bytes());
    const double estimate = double(world_bytes_estimate(scene.def));
    SCOPED_TRACE(discs ? "discs" : "linked bodies");
    EXPECT_GE(estimate, held);
    EXPECT_LE(estimate, 2.0 * held);  // an upper bound, not an absurd one
  }
}

TEST(CommandMemoryLimits, SumsSaturateAndNameTheLargestTerm) {
  const std::vector<MemoryTerm> terms{{.what = "a", .bytes = UINT64_MAX, .way_out = "less a"},
                                      {.what = "b", .bytes = 5u << 20, .way_out = "less b"}};
  EXPECT_EQ(total_bytes(terms), UINT64_MAX);
  const std::string e = refusal(terms, "run");
  EXPECT_NE(e.find("a dominates: less a"), std::string::npos) << e;
}

}  // namespace
}  // namespace fixstep::cli
