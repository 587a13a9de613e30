// fixstep::app::run: a game type given the headless run, record, replay with verification, the
// sync test and the command line, checked through its outputs and exit statuses.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fixstep/app/app.hpp>
#include <fixstep/app/game_model.hpp>
#include <fixstep/app/game_play.hpp>
#include <fixstep/core/components.hpp>
#include <fixstep/core/input.hpp>
#include <fixstep/core/recording.hpp>
#include <fixstep/core/rules.hpp>
#include <fixstep/core/shape.hpp>
#include <fixstep/core/world_def.hpp>
#include <fixstep/core/world_settings.hpp>
#include <fixstep/io/atomic_output.hpp>
#include <fixstep/io/recording_file.hpp>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace fixstep;

constexpr double dt = 0.01;  // s

/// A ball dropped from 10 m; the rules count the ticks after which it is still above 5 m.
/// Semi-implicit Euler from rest: y_n = 10 - g dt² n(n+1)/2, so y_n > 5 exactly for
/// n(n+1) < 10 / (g dt²) = 10193.7..., that is n <= 100: 100 ticks once the run is long enough.
struct Drop {
  int above = 0;
  void setup(WorldDef& level) {
    level.settings.dt = dt;
    BodyDef ball;
    ball.name = "ball";
    ball.body = {.mass = 1.0, .position = {0.0, 10.0}};
    ball.gravity = Gravity{};
    level.bodies.push_back(ball);
  }
  void rules(World& world, const TickInput&) {
    if (world.body(world.find("ball")).position.y > 5.0) ++above;
  }
  void autopilot(std::int64_t frame, const World& world, InputSampler& sampler) const {
    if (frame == 30) sampler.apply_impulse(world.find("ball"), {1.0, 0.0});  // N·s
  }
  [[nodiscard]] std::string summary() const { return "above=" + std::to_string(above); }
};

/// Rules that read state kept outside the world and the game (a global): a rollback cannot put
/// it back, so the sync test must find the difference.
int outside_counter = 0;
struct Leaky : Drop {
  void rules(World& world, const TickInput& input) {
    Drop::rules(world, input);
    if (++outside_counter % 50 == 0) world.set_velocity(world.find("ball"), {0.0, 1.0});
  }
};

/// Drop, but the rules name the ball by the handle setup() kept (WorldDef::add_body) and by the
/// user data it gave the ball: both must reach the copy that plays, replays and rolls back.
struct Tagged {
  int above = 0;
  Entity ball = null_entity;
  void setup(WorldDef& level) {
    level.settings.dt = dt;
    BodyDef def;
    def.body = {.mass = 1.0, .position = {0.0, 10.0}};
    def.gravity = Gravity{};
    def.user_data = 7;
    ball = level.add_body(def);
  }
  void rules(World& world, const TickInput&) {
    if (world.user_data(ball) == 7 && world.body(ball).position.y > 5.0) ++above;
  }
  [[nodiscard]] std::string summary() const { return "above=" + std::to_string(above); }
};

const app::Settings settings{.name = "drop", .width = 160, .height = 90};

/// run(game, settings, args...) with standard output captured into `out`.
template <class G>
int run(const G& game, std::initializer_list<std::string> args, std::string* out = nullptr) {
  std::vector<std::string> words{"drop"};
  words.insert(words.end(), args);
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  testing::internal::CaptureStdout();
  const int status = app::run(game, settings, int(argv.size()), argv.data());
  const std::string printed = testing::internal::GetCapturedStdout();
  if (out != nullptr) *out = printed;
  return status;
}

class AppRun : public testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        std::filesystem::temp_directory_path() / ("fixstep_app_run_" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  [[nodiscard]] std::string path(const char* name) const { return (dir_ / name).string(); }
  std::filesystem::path dir_;
};

TEST_F(AppRun, HeadlessRunsTheRulesEveryTick) {
  std::string out;
  ASSERT_EQ(run(Drop{}, {"--frames", "121"}, &out), 0);
  // 120 frames of 1/60 s = 2 s = 200 ticks of 0.01 s: the ball fell below 5 m after tick 100.
  EXPECT_NE(out.find("ticks=200 "), std::string::npos) << out;
  EXPECT_NE(out.find("above=100\n"), std::string::npos) << out;
}

// A stop request that tears a tick (StopRequested inside World::step) leaves the world in no
// tick's state: finish_stopped(true) writes the recording up to the last complete tick, whose
// hash it stored, never the torn state's, so the recording replays. While the game plays, the
// recording is in its temporary file (streamed), not under its name.
TEST_F(AppRun, AStoppedRecordingEndsAtTheLastCompleteTickAndReplays) {
  const std::string rec = path("stopped.rec");
  std::uint64_t ticks = 0;
  {
    app::detail::GamePlay play(
        app::detail::load_level(app::detail::GameModel<Drop>(Drop{}), settings, ""), settings, rec);
    for (int frame = 0; frame < 5; ++frame) play.advance(0.1);
    World& world = play.session().simulation();
    ticks = world.tick();
    ASSERT_GT(ticks, 30u);
    EXPECT_TRUE(std::filesystem::exists(temporary_file_for(rec)));
    EXPECT_FALSE(std::filesystem::exists(rec));
    world.set_velocity(world.find("ball"), {3.0, 0.0});  // a torn tick's state: no tick's
    testing::internal::CaptureStdout();
    play.finish_stopped(true);
    const std::string out = testing::internal::GetCapturedStdout();
    EXPECT_NE(out.find("recorded " + std::to_string(ticks) + " ticks"), std::string::npos) << out;
    EXPECT_EQ(out.find("ticks="), std::string::npos) << "a torn state has no summary: " << out;
  }
  EXPECT_FALSE(std::filesystem::exists(temporary_file_for(rec)));
  std::string replayed;
  EXPECT_EQ(run(Drop{}, {"--replay", rec}, &replayed), 0) << replayed;
  EXPECT_NE(replayed.find("ticks=" + std::to_string(ticks) + " "), std::string::npos) << replayed;
}

TEST_F(AppRun, RecordingReplaysWithTheRulesAndRefusesATamperedCopy) {
  const std::string rec = path("drop.rec");
  std::string played, replayed;
  ASSERT_EQ(run(Drop{}, {"--frames", "61", "--record", rec}, &played), 0);
  ASSERT_EQ(run(Drop{}, {"--replay", rec}, &replayed), 0) << replayed;
  EXPECT_EQ(played.substr(0, played.find('\n')), replayed.substr(0, replayed.find('\n')));
  EXPECT_NE(replayed.find("above=100\nverified=101\n"), std::string::npos) << replayed;

  // The autopilot's impulse made three times as strong: the state differs from that tick on.
  std::stringstream text;
  text << std::ifstream(rec).rdbuf();
  std::string edited = text.str();
  const std::size_t at = edited.find(",1,0\n", edited.find("impulse="));
  ASSERT_NE(at, std::string::npos) << edited.substr(0, 400);
  edited.replace(at, 4, ",3,0");
  const std::string tampered = path("tampered.rec");
  std::ofstream(tampered) << edited;
  testing::internal::CaptureStderr();
  EXPECT_EQ(run(Drop{}, {"--replay", tampered}), 4);
  EXPECT_NE(testing::internal::GetCapturedStderr().find("tampered.rec diverged at tick "),
            std::string::npos);
}

TEST_F(AppRun, SyncTestPassesForRulesInTheGameAndFailsForStateOutsideIt) {
  std::string live, synced;
  ASSERT_EQ(run(Drop{}, {"--frames", "121"}, &live), 0);
  ASSERT_EQ(run(Drop{}, {"--frames", "121", "--sync-test", "7"}, &synced), 0) << synced;
  EXPECT_EQ(live.substr(0, live.find('\n')), synced.substr(0, synced.find('\n')));
  outside_counter = 0;
  EXPECT_EQ(run(Leaky{}, {"--frames", "121", "--sync-test", "7"}), 8);
}

TEST_F(AppRun, WhatSetupKeepsInTheGameReachesEveryMode) {
  const std::string rec = path("tagged.rec");
  std::string played, replayed, synced;
  ASSERT_EQ(run(Tagged{}, {"--frames", "121", "--record", rec}, &played), 0);
  EXPECT_NE(played.find("above=100\n"), std::string::npos) << played;  // as Drop's
  ASSERT_EQ(run(Tagged{}, {"--replay", rec}, &replayed), 0) << replayed;
  EXPECT_NE(replayed.find("above=100\nverified=201\n"), std::string::npos) << replayed;
  ASSERT_EQ(run(Tagged{}, {"--frames", "121", "--sync-test", "7"}, &synced), 0) << synced;
  EXPECT_NE(synced.find("above=100\n"), std::string::npos) << synced;
}

TEST_F(AppRun, LastFrameOfAHeadlessRunIsWritten) {
  const std::string png = path("last.png");
  ASSERT_EQ(run(Drop{}, {"--frames", "10", "--last-frame", png}), 0);
  ASSERT_TRUE(std::filesystem::exists(png));
  // A PNG of 160 x 90 pixels: the signature, then IHDR's width and height (big-endian).
  std::ifstream file(png, std::ios::binary);
  unsigned char head[24] = {};
  file.read(reinterpret_cast<char*>(head), sizeof head);
  EXPECT_EQ(head[1], 'P');
  EXPECT_EQ((head[18] << 8) | head[19], 160);
  EXPECT_EQ((head[22] << 8) | head[23], 90);
  EXPECT_EQ(run(Drop{}, {"--last-frame", png}), 2);  // a window until quit has no last frame
  EXPECT_EQ(run(Drop{}, {"--frames", "10", "--sync-test", "2", "--last-frame", png}), 2);
}

/// The files in `dir`, sorted.
std::vector<std::string> names_in(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

/// The first two columns (frame, tick) of each row of the manifest `csv`, after its header.
std::vector<std::string> frames_and_ticks(const std::filesystem::path& csv) {
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "frame,tick,t,alpha,state_hash,energy,balance");
  std::vector<std::string> rows;
  while (std::getline(in, line)) rows.push_back(line.substr(0, line.find(',', line.find(',') + 1)));
  return rows;
}

// --replay --out DIR --every K: each frame written is named by its frame index (0, K, 2K, ...,
// and the last), not by how many were written before it, and frames.csv gives each its tick.
// 10 frames of 1/60 s recorded: ticks of 0.01 s, so frame f is tick floor(100 f / 60): the
// recording ends at tick 15, frame 9.
TEST_F(AppRun, ReplayedFramesAreNamedByTheirFrameIndexAndListedWithTheirTicks) {
  const std::string rec = path("ten.rec");
  std::string recorded;
  ASSERT_EQ(run(Drop{}, {"--frames", "10", "--record", rec}, &recorded), 0);
  ASSERT_NE(recorded.find("ticks=15 "), std::string::npos) << recorded;
  std::string replayed;
  ASSERT_EQ(run(Drop{}, {"--replay", rec, "--out", path("every3"), "--every", "3"}, &replayed), 0)
      << replayed;
  EXPECT_EQ(names_in(path("every3")),
            (std::vector<std::string>{"frame_000000.png", "frame_000003.png", "frame_000006.png",
                                      "frame_000009.png", "frames.csv"}));
  EXPECT_EQ(frames_and_ticks(dir_ / "every3" / "frames.csv"),
            (std::vector<std::string>{"0,0", "3,5", "6,10", "9,15"}));
  // The last frame is written when K does not divide it, under its own index.
  ASSERT_EQ(run(Drop{}, {"--replay", rec, "--out", path("every4"), "--every", "4"}), 0);
  EXPECT_EQ(names_in(path("every4")),
            (std::vector<std::string>{"frame_000000.png", "frame_000004.png", "frame_000008.png",
                                      "frame_000009.png", "frames.csv"}));
  EXPECT_EQ(frames_and_ticks(dir_ / "every4" / "frames.csv"),
            (std::vector<std::string>{"0,0", "4,6", "8,13", "9,15"}));
  // A headless run's --out: every frame, each listed.
  ASSERT_EQ(run(Drop{}, {"--frames", "4", "--out", path("all")}), 0);
  EXPECT_EQ(names_in(path("all")),
            (std::vector<std::string>{"frame_000000.png", "frame_000001.png", "frame_000002.png",
                                      "frame_000003.png", "frames.csv"}));
  EXPECT_EQ(frames_and_ticks(dir_ / "all" / "frames.csv"),
            (std::vector<std::string>{"0,0", "1,1", "2,3", "3,5"}));
}

TEST_F(AppRun, BadCommandLinesExitTwo) {
  EXPECT_EQ(run(Drop{}, {"--frames", "0"}), 2);
  EXPECT_EQ(run(Drop{}, {"--frames", "1.5"}), 2);
  EXPECT_EQ(run(Drop{}, {"--out", path("frames")}), 2);  // no --frames: a window has no --out
  EXPECT_EQ(run(Drop{}, {"--replay", "x.rec", "--record", "y.rec"}), 2);
  EXPECT_EQ(run(Drop{}, {"--sync-test", "4"}), 2);  // no --frames
  EXPECT_EQ(run(Drop{}, {"--bogus"}), 2);
  EXPECT_FALSE(std::filesystem::exists(path("frames")));
}

TEST_F(AppRun, MissingRecordingExitsOneNamingIt) {
  testing::internal::CaptureStderr();
  EXPECT_EQ(run(Drop{}, {"--replay", path("none.rec")}), 1);
  EXPECT_NE(testing::internal::GetCapturedStderr().find("none.rec"), std::string::npos);
}

/// A game whose drawing is one HUD line.
struct Scored : Drop {
  void draw(app::Overlay& overlay) const { overlay.text("score 0"); }
};

TEST(AppDraw, TheHintGivesAStatusLinePerLineOfIt) {
  // The window's hint is the game's keys and the window's on two lines (one line of both is
  // wider than the HUD beside a game's field): after the game's own lines, in order.
  WorldDef level;
  Scored game;
  game.setup(level);
  Session session(level, SessionSettings{.width = 64, .height = 36});
  const app::detail::GameModel<Scored> model(game);
  app::Overlay overlay;
  app::detail::draw_game(session, model, overlay, "mouse: aim\nr: restart   esc: quit");
  const auto lines = overlay.lines();
  EXPECT_EQ(std::vector<std::string>(lines.begin(), lines.end()),
            (std::vector<std::string>{"score 0", "mouse: aim", "r: restart   esc: quit"}));
  app::detail::draw_game(session, model, overlay, "autopilot");
  EXPECT_EQ(overlay.lines().size(), 2u);
  app::detail::draw_game(session, model, overlay, {});
  EXPECT_EQ(overlay.lines().size(), 1u);
}

}  // namespace

namespace {

/// A box on a ground plane, whose pre_solve() (a game's hook) lets the box through the ground
/// once `ghost` is on: it then falls through, in every mode the game is stepped in.
struct Ghost {
  bool ghost = false;
  Entity box{};
  void setup(WorldDef& level) {
    level.settings.dt = dt;
    level.settings.contacts = ContactSettings{};
    level.planes.push_back(PlaneDef{});  // y = 0, normal +y
    BodyDef def;
    def.name = "box";
    def.body = {.mass = 1.0, .position = {0.0, 0.5}};
    def.gravity = Gravity{};
    def.shapes = {make_box(0.5, 0.5)};
    level.add_body(def);
    box = level.find_body("box");
  }
  void rules(World& world, const TickInput&) {
    if (world.tick() == 100) ghost = true;  // a rule: from tick 100 the box is a ghost
  }
  [[nodiscard]] bool pre_solve(const PreSolveContact& c) const { return !(ghost && c.b == box); }
  [[nodiscard]] std::string summary() const { return ghost ? "ghost" : "solid"; }
};

/// Rules before the step (Settings::rules_before_step) moving a kinematic body from the tick's
/// held action: it moves in the tick the action is pressed.
struct Mover {
  Entity body{};
  double x_at_press = -1.0;
  void setup(WorldDef& level) {
    level.settings.dt = dt;
    BodyDef def;
    def.name = "slider";
    def.type = BodyType::kinematic;
    body = level.add_body(def);
  }
  void rules(World& world, const TickInput& in) {
    world.set_velocity(body, {(in.held & (1u << 9)) != 0 ? 1.0 : 0.0, 0.0});
  }
  [[nodiscard]] std::string summary() const { return ""; }
};

TEST_F(AppRun, AGamesPreSolveActsLiveInReplayAndInTheSyncTest) {
  // The hook itself: the box rests on the plane until tick 100, then falls through it.
  Ghost game;
  WorldDef def;
  game.setup(def);
  World world(def);
  world.set_pre_solve(
      [](const PreSolveContact& c, void* g) { return static_cast<Ghost*>(g)->pre_solve(c); },
      &game);
  for (int t = 0; t < 200; ++t) {
    game.rules(world, TickInput{});
    world.step();
    if (t == 99) {
      EXPECT_NEAR(world.body(game.box).position.y, 0.5, 0.01);  // resting
    }
  }
  EXPECT_LT(world.body(game.box).position.y, -3.0);  // fell through once a ghost
  // app::run installs it in every mode: the same final state live (200 ticks), in the replay
  // of that run, and under the sync test, and it is that state.
  const auto hash = [](const std::string& out) {
    const auto at = out.find("state_hash=");
    return at == std::string::npos ? std::string("none") : out.substr(at, 27);
  };
  std::string live, replayed, sync;
  ASSERT_EQ(run(Ghost{}, {"--frames", "121", "--record", path("g.rec")}, &live), 0);
  ASSERT_EQ(run(Ghost{}, {"--replay", path("g.rec")}, &replayed), 0) << replayed;
  ASSERT_EQ(run(Ghost{}, {"--frames", "121", "--sync-test", "8"}, &sync), 0) << sync;
  EXPECT_EQ(hash(live), fmt::format("state_hash={:016x}", world.state_hash()).substr(0, 27));
  EXPECT_EQ(hash(replayed), hash(live));
  EXPECT_EQ(hash(sync), hash(live));
}

TEST_F(AppRun, RulesBeforeTheStepActInTheTickOfTheirInput) {
  // A script holds action bit 9 from tick 3: the slider moves in tick 3 (before the step), so
  // after 10 ticks it has moved 7 ticks of 1 m/s.
  const std::string script = path("s.toml");
  std::ofstream(script) << "[[at]]\ntick = 3\npress = [\"pointer_secondary\"]\n";
  app::Settings before = settings;
  before.rules_before_step = true;
  std::vector<std::string> words{"drop", "--frames", "7",          "--input",
                                 script, "--record", path("m.rec")};
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  testing::internal::CaptureStdout();
  ASSERT_EQ(app::run(Mover{}, before, int(argv.size()), argv.data()), 0);
  (void)testing::internal::GetCapturedStdout();
  const Recording rec = read_recording(path("m.rec"));
  WorldDef def;
  Mover m;
  m.setup(def);
  World world(def);
  TickRules rules;
  rules.before_tick = [&m](World& w, const TickInput& in) { m.rules(w, in); };
  const ReplayReport report = replay(world, rec, rules);
  ASSERT_TRUE(report.ok());
  EXPECT_NEAR(world.body(m.body).position.x, (double(rec.ticks) - 3.0) * dt, 1e-12);
  // With the rules after the step instead, the slider moves a tick later: the recording's
  // hash after tick 3 (its 4th) is the first that differs.
  World late(def);
  TickRules after;
  after.after_tick = [&m](World& w, const TickInput& in) { m.rules(w, in); };
  const ReplayReport late_report = replay(late, rec, after);
  ASSERT_TRUE(late_report.mismatch.has_value());
  EXPECT_EQ(late_report.mismatch->tick, 4u);
}

}  // namespace
