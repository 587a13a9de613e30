// The limits on work and memory (engine/core/src/limits.cpp), where they are checked (the scene
// loader, check_limits, the recording reader), the guard run once per load, the engine's
// progress reports, and the streaming recorder (engine/io/src/recording_writer.cpp).
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fixstep/core/components.hpp>
#include <fixstep/core/input.hpp>
#include <fixstep/core/limits.hpp>
#include <fixstep/core/recording.hpp>
#include <fixstep/core/work_progress.hpp>
#include <fixstep/core/world.hpp>
#include <fixstep/core/world_def.hpp>
#include <fixstep/core/world_settings.hpp>
#include <fixstep/io/recording_writer.hpp>
#include <fixstep/scene/scene.hpp>
#include <fixstep/scene/scene_stability.hpp>
#include <fstream>
#include <sstream>
#include <string>

#include "fixstep/core/definition_checks.hpp"
#include "fixstep/io/command_limits.hpp"
#include "fixstep/io/recording_file.hpp"
#include "link_between.hpp"
#include "scene_guard.hpp"

namespace fixstep {
namespace {
using test::check_scene_network;

/// A scene of a columns × rows grid of linked bodies (structural links only), with `world`
/// added to [world].
std::string grid_scene(int columns, int rows, const std::string& world) {
  return "[world]\ndt = 0.01\n" + world +
         "\n[[grid]]\nname = \"g\"\ncolumns = " + std::to_string(columns) +
         "\nrows = " + std::to_string(rows) +
         "\norigin = [0.0, 0.0]\nspacing = [0.1, -0.1]\n"
         "body = { mass = 1.0 }\nlink = { stiffness = 10.0, damping = 0.1 }\n";
}

/// A chain of n bodies on links of rest length 1 m.
WorldDef chain(std::size_t n) {
  WorldDef def;
  def.settings.dt = 0.01;
  for (std::size_t i = 0; i < n; ++i) {
    BodyDef b;
    b.body = {1.0, {double(i), 0.0}, {}};
    def.bodies.push_back(b);
    if (i > 0)
      def.links.push_back(fixstep::test::link_between(i - 1, i, LinkSpring{10.0, 0.1, 1.0}));
  }
  return def;
}

TEST(Limits, TickWorkCountsBodiesLinksSubstepsAndTheImplicitSolve) {
  WorldDef def = chain(10);  // 10 bodies, 9 links
  def.settings.substeps = 3;
  EXPECT_EQ(tick_work(def), 19u * 3u);
  def.settings.integrator = Integrator::implicit_euler;
  // + each body 64·√10 (ceil: 203) times for the sparse solve
  EXPECT_EQ(tick_work(def), (19u + 10u * 203u) * 3u);
  def.links.clear();
  EXPECT_EQ(tick_work(def), 10u * 3u);  // no network: no solve
  EXPECT_EQ(implicit_solve_bytes(def.bodies, def.links, def.settings), 0u);
}

TEST(Limits, TickWorkCountsPlanesAndDiscs) {
  WorldDef def;
  def.settings.dt = 0.01;
  def.settings.substeps = 2;
  for (int i = 0; i < 4; ++i) {
    BodyDef b;
    b.type = i == 3 ? BodyType::static_body : BodyType::dynamic;
    b.body = {1.0, {double(i), 0.0}, {}};
    if (i > 0) b.collider = Collider{.radius = 0.1, .collide = i != 2};
    def.bodies.push_back(b);
  }
  def.planes.assign(5, PlaneDef{});
  // 4 bodies × 2 substeps + 2 dynamic colliders × 5 planes (the static one meets none)
  EXPECT_EQ(tick_work(def), 4u * 2u + 2u * 5u * plane_pair_work);
  def.settings.contacts = ContactSettings{};
  // + the 2 colliders that collide (body 2 does not) × disc_work
  EXPECT_EQ(tick_work(def), 4u * 2u + 2u * 5u * plane_pair_work + 2u * disc_work);
  // The resting solver's iterations beyond the default 20 + 10 weigh in: 1000 + 1000 is 67
  // times the sweeps (they counted as 20 + 10).
  def.settings.contacts->velocity_iterations = 1000;
  def.settings.contacts->position_iterations = 1000;
  EXPECT_EQ(tick_work(def),
            4u * 2u + 2u * 5u * plane_pair_work + 2u * ((disc_work * 2000 + 29) / 30));
  def.settings.contacts->velocity_iterations = 5;  // fewer: the broadphase's share stays
  def.settings.contacts->position_iterations = 1;
  EXPECT_EQ(tick_work(def), 4u * 2u + 2u * 5u * plane_pair_work + 2u * disc_work);
}

TEST(Limits, PlanesTimesCollidersBeyondATickAreRefusedNamingThePlanes) {
  // 40 000 dynamic colliders × 30 000 planes: 1.2e9 plane tests a tick, some 10 s.
  std::vector<BodyDef> bodies(40'000);
  for (BodyDef& b : bodies) b.collider = Collider{.radius = 0.1};
  const std::vector<PlaneDef> planes(30'000);
  const WorldSettings settings{.dt = 0.01};
  try {
    check_world_limits(bodies, {}, planes, settings);
    FAIL() << "1.2e9 plane tests a tick accepted";
  } catch (const LimitError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("40000 bodies + 0 links × 1 substeps + 40000 colliders × 30000 planes = "
                     "1200040000 body-substeps per tick"),
              std::string::npos)
        << m;
    EXPECT_NE(m.find("use fewer planes or fewer colliders"), std::string::npos) << m;
  }
  EXPECT_NO_THROW(check_world_limits(bodies, {}, std::span(planes).first(20'000), settings));
}

// Segments were not counted: 20 000 segments over 10^4 discs took 31 s a tick (a disc's query
// may return every segment). Counted as planes are, at segment_pair_work each, they are
// refused at load, by check_limits and by the scene loader at the first [[segment]] or
// [[polyline]].
TEST(Limits, SegmentsTimesCollidersBeyondATickAreRefusedNamingTheSegments) {
  WorldDef def;
  def.settings.dt = 0.01;
  for (int i = 0; i < 10'000; ++i) {
    BodyDef b;
    b.body = {1.0, {0.3 * (i % 100), 1.0 + 0.3 * (i / 100)}, {}};
    b.collider = Collider{.radius = 0.1};
    def.bodies.push_back(b);
  }
  for (int i = 0; i < 20'000; ++i) {
    def.segments.push_back(SegmentDef{.a = {0.01 * i, 0.0}, .b = {0.01 * i + 0.01, 0.0}});
  }
  // 10^4 bodies × 1 substep + 10^4 colliders × 2·10^4 segments × segment_pair_work
  EXPECT_EQ(tick_work(def), 10'000u + 10'000u * 20'000u * segment_pair_work);
  try {
    check_limits(def);
    FAIL() << "2e8 segment tests a tick accepted";
  } catch (const LimitError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("10000 colliders × 20000 segments × 16 = 3200010000 body-substeps per tick"),
              std::string::npos)
        << m;
    EXPECT_NE(m.find("use fewer segments (a polyline's points) or fewer colliders"),
              std::string::npos)
        << m;
  }
  def.segments.resize(5'000);  // 8e8 + 10^4: within the limit
  EXPECT_NO_THROW(check_limits(def));
}

TEST(Limits, ThePolylineBeyondATickIsRefusedAtItsTable) {
  // 2000 discs and a polyline of 40 000 points: 2000 × 39 999 × 16 = 1.28e9.
  std::string scene =
      "[world]\ndt = 0.01\n[[grid]]\nname = \"g\"\ncolumns = 50\nrows = 40\n"
      "origin = [0.0, 10.0]\nspacing = [0.5, 0.5]\n"
      "body = { mass = 1.0, radius = 0.1 }\n"
      "[[polyline]]\npoints = [";
  for (int i = 0; i < 40'000; ++i) scene += fmt::format("[{}, {}],", 0.01 * i, (i % 2) * 0.01);
  scene += "]\n";
  try {
    (void)parse_scene(scene, "long.toml");
    FAIL() << "a polyline of 40 000 points over 2000 discs accepted";
  } catch (const SceneError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("long.toml:"), std::string::npos) << m;
    EXPECT_NE(m.find("polyline[0]: "), std::string::npos) << m;
    EXPECT_NE(m.find("2000 colliders × 39999 segments"), std::string::npos) << m;
  }
}

TEST(Limits, CheckLimitsRefusesATickBeyondTheWorkLimitBeforeStepping) {
  WorldDef def = chain(1000);  // 1999 body-substeps a substep
  def.settings.substeps = 1'000'000;
  try {
    check_limits(def);
    FAIL() << "a tick of 2e9 body-substeps was accepted";
  } catch (const LimitError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("1000 bodies + 999 links × 1000000 substeps = 1999000000 body-substeps"),
              std::string::npos)
        << m;
    EXPECT_NE(m.find("use fewer substeps"), std::string::npos) << m;
  }
  def.settings.substeps = 500'000;  // 9.995e8: within
  EXPECT_NO_THROW(check_limits(def));
}

TEST(Limits, WorldRefusesATickBeyondTheWorkLimitBeforeItBuilds) {
  // World(def) checks the limits before it builds anything: a body with a NaN mass, which the
  // build would name, is not reached.
  WorldDef def = chain(1000);
  def.settings.substeps = 1'000'000;
  def.bodies.back().body.mass = std::nan("");
  EXPECT_THROW((void)World(def), LimitError);
  def.settings.substeps = 1;
  EXPECT_THROW((void)World(def), std::invalid_argument);  // now the build names the body
}

TEST(Limits, TheSceneLoaderNamesTheSubstepsLine) {
  // 300 × 300 bodies and 179 400 links at 10^6 substeps: hours a tick before the limit.
  const std::string text = grid_scene(300, 300, "substeps = 1000000");
  try {
    (void)parse_scene(text, "big.toml");
    FAIL() << "refused only when stepped";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.line(), 3u) << e.what();
    EXPECT_EQ(e.key(), "world.substeps") << e.what();
    EXPECT_NE(std::string(e.what()).find("body-substeps per tick"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW((void)parse_scene(grid_scene(300, 300, "substeps = 100"), "ok.toml"));
}

TEST(Limits, ImplicitEulerOnALargeNetworkIsRefusedAtLoadNamingTheWayOut) {
  // 600 × 600 = 360 000 bodies with rest-length links: SparseLU over 720 000 unknowns.
  const std::string text = grid_scene(600, 600, "integrator = \"implicit_euler\"");
  try {
    (void)parse_scene(text, "cloth.toml");
    FAIL() << "accepted: the first tick would ask Eigen for gigabytes";
  } catch (const SceneError& e) {
    const std::string m = e.what();
    EXPECT_EQ(e.key(), "world.integrator") << m;
    EXPECT_EQ(e.line(), 3u) << m;
    EXPECT_NE(m.find("implicit_euler on 360000 linked bodies"), std::string::npos) << m;
    EXPECT_NE(m.find("semi_implicit_euler with substeps"), std::string::npos) << m;
  }
  // The body bound (a stop request within a second): 160 × 160 = 25 600 refused, 150 × 150 not.
  try {
    (void)parse_scene(grid_scene(160, 160, "integrator = \"implicit_euler\""), "net.toml");
    FAIL() << "accepted: one factorisation would keep a stop request waiting over a second";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key(), "world.integrator") << e.what();
    EXPECT_NE(std::string(e.what()).find("at most 25000 may be solved together"), std::string::npos)
        << e.what();
  }
  EXPECT_NO_THROW(
      (void)parse_scene(grid_scene(150, 150, "integrator = \"implicit_euler\""), "ok.toml"));
  // The estimate grows faster than the bodies (fill-in), and a small network is far within.
  WorldDef small = chain(100), large = chain(10000);
  small.settings.integrator = large.settings.integrator = Integrator::implicit_euler;
  const auto bytes = [](const WorldDef& d) {
    return implicit_solve_bytes(d.bodies, d.links, d.settings);
  };
  EXPECT_GT(bytes(large), 50 * bytes(small));
  EXPECT_LT(bytes(large), max_implicit_solve_bytes / 10);
}

TEST(Limits, CommandWorkIsBoundedInTicksAndInBodySubsteps) {
  EXPECT_NO_THROW(check_command_work(max_command_ticks, 10'000, "--steps"));  // 1e13
  EXPECT_THROW(check_command_work(max_command_ticks + 1, 1, "--steps"), LimitError);
  EXPECT_THROW(check_command_work(max_command_ticks, 10'001, "--steps"), LimitError);
  try {
    check_command_work(2'000'000'000, 4, "--steps 2000000000");
    FAIL();
  } catch (const LimitError& e) {
    EXPECT_NE(std::string(e.what()).find("--steps 2000000000: 2000000000 ticks"), std::string::npos)
        << e.what();
  }
}

/// A recording's header with `hash_every`, then `body` (tick, hash and end lines).
std::string recording_text(std::uint64_t hash_every, const std::string& body) {
  return "fixstep-recording 2\nscene s.toml\ndefinition 0000000000000001\n"
         "integrator semi_implicit_euler\nprecision f64\ndt 0.01\nsubsteps 1\nhash_every " +
         std::to_string(hash_every) +
         "\ntick 0 push=0,0 held=0 pressed=0 released=0 pointer=0,0 drag=none\n" + body;
}

std::string read_error(const std::string& text) {
  try {
    (void)parse_recording(text, "tiny.rec");
  } catch (const RecordingError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(Limits, ATinyRecordingCannotClaimABillionTicks) {
  // 300 bytes claiming 10^9 ticks: replayed for 35 s before its final hash was found wrong.
  EXPECT_NE(read_error(recording_text(1, "end 1000000000 0000000000000002\n"))
                .find("tiny.rec:10: end: 1000000000 ticks claimed, but no state hash between "
                      "ticks 0 and 1000000000"),
            std::string::npos);
  EXPECT_NE(read_error(recording_text(1'000'000'000, "end 1000000000 0000000000000002\n"))
                .find("tiny.rec:8: hash_every: 1000000000 ticks between state hashes"),
            std::string::npos);
  // Hashes as a recorder writes them read, also when the last stretch is shorter.
  EXPECT_EQ(read_error(recording_text(
                4, "hash 4 0000000000000003\nhash 8 0000000000000004\nend 10 0000000000000005\n")),
            "accepted");
  EXPECT_NE(read_error(recording_text(4, "hash 4 0000000000000003\nend 10 0000000000000005\n"))
                .find("no state hash between ticks 4 and 10"),
            std::string::npos);
}

TEST(Limits, TheStabilityGuardRunsOncePerSceneLoad) {
  const Scene scene = parse_scene(grid_scene(30, 30, ""), "g.toml");
  std::uint64_t iterations = 0;
  const WorkProgressScope count(
      [&](std::string_view what, std::string_view, std::uint64_t, std::uint64_t) {
        if (what == "stability guard") ++iterations;
      });
  (void)check_scene_network(scene);
  const std::uint64_t once = iterations;
  ASSERT_GT(once, 0u);  // the guard's power iteration reports its progress
  iterations = 0;
  (void)World(scene.def);  // the guard inside World(def), once
  EXPECT_EQ(iterations, once);
}

TEST(Limits, ReplayReportsItsProgress) {
  WorldDef def = chain(3);
  World sim = World(def);
  Recorder recorder(def, "c.toml", 100);
  for (int t = 0; t < 5000; ++t) {
    sim.step(TickInput{.tick = std::uint64_t(t)});
    recorder.record(TickInput{}, sim);
  }
  const Recording rec = recorder.finish(sim);
  World again = World(def);
  std::uint64_t last = 0, total = 0;
  const WorkProgressScope seen(
      [&](std::string_view what, std::string_view unit, std::uint64_t done, std::uint64_t all) {
        EXPECT_EQ(what, "replay");
        EXPECT_EQ(unit, "tick");
        last = done, total = all;
      });
  EXPECT_TRUE(replay(again, rec).ok());
  EXPECT_EQ(last, 4096u);
  EXPECT_EQ(total, 5000u);
}

std::string slurp(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Steps `def` `ticks` ticks with changing input into a Recorder and a RecordingWriter.
std::string stream_and_compare(const WorldDef& def, const std::filesystem::path& file,
                               std::uint64_t ticks, std::uint64_t hash_every,
                               Recording& in_memory) {
  World sim = World(def);
  Recorder recorder(def, "c.toml", hash_every);
  RecordingWriter writer(def, "c.toml", hash_every, file);
  for (std::uint64_t t = 0; t < ticks; ++t) {
    TickInput in{.tick = t};
    if (t % 7 < 3) in.push = {double(t % 5), -1.0}, in.held = button_right;
    sim.step(in);
    recorder.record(in, sim);
    writer.record(in, sim);
  }
  in_memory = recorder.finish(sim);
  EXPECT_FALSE(std::filesystem::exists(file)) << "the final name before finish()";
  writer.finish(sim);
  return slurp(file);
}

TEST(Limits, TheStreamingRecorderWritesRecordersBytesAndOnlyAtTheEnd) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("fixstep_limits_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  for (const std::uint64_t hash_every : {1u, 3u, 1000u}) {
    std::filesystem::remove(dir / "s.rec");
    Recording rec;
    const std::string text = stream_and_compare(chain(4), dir / "s.rec", 2000, hash_every, rec);
    EXPECT_EQ(text, format_recording(rec)) << hash_every;
    EXPECT_TRUE(replay(chain(4), parse_recording(text, "s.rec")).ok());
  }
  {  // abandoned (an exception, an early return): neither the file nor the temporary remains
    RecordingWriter writer(chain(2), "c.toml", 1, dir / "gone.rec");
    World sim = World(chain(2));
    sim.step(TickInput{});
    writer.record(TickInput{}, sim);
  }
  std::size_t left = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    left += entry.path().filename() != "s.rec";
  }
  EXPECT_EQ(left, 0u);
  EXPECT_THROW(RecordingWriter(chain(2), "c.toml", max_hash_every + 1, dir / "x.rec"),
               std::invalid_argument);
  EXPECT_THROW(RecordingWriter(chain(2), "c.toml", 1, dir / "no_dir" / "x.rec"),
               std::runtime_error);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace fixstep
