// A fixstep prototype, written by `fixstep new`: a hook slides along the top, a rope hangs from
// it with a claw at its end, and balls fall from the sky. Catch them with the claw.
//
//   PROGRAM                          play in a window (arrows, Enter; r restart, Esc quit)
//   PROGRAM --record FILE            play, and record the session into FILE
//   PROGRAM --frames N [--out DIR]   N frames headless, played by the autopilot (PNGs into DIR)
//   PROGRAM --frames N --record FILE record the autopilot's game headless
//   PROGRAM --replay FILE            re-simulate a recording and verify every state hash
//   (--scene FILE plays another level; the default is this project's scene.toml)
//
// Every tick runs the same steps, in the window, headless and in a replay:
//   input           the keys (or the autopilot), sampled for this tick by an InputSampler
//   per-body input  what the keys do to bodies: the hook's velocity, a pull or a swing of the claw
//   step, rules     sim.step(input), then the game's rules (catch, miss, drop again): TickRules
//   draw            the Session draws the state between the last two ticks
// A recording holds the input only: a replay runs the same rules on it and must reach the
// same states, bit for bit.
#include <charconv>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <fixstep/capture.hpp>
#include <fixstep/recording.hpp>
#include <fixstep/rules.hpp>
#include <fixstep/scene.hpp>
#include <fixstep/session.hpp>
#include <fixstep/window.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <thread>
#include <vector>

#include "fixstep/recording_file.hpp"
#include "fixstep/summary.hpp"

namespace {

using namespace fixstep;

constexpr const char* program = PROGRAM_NAME;  // the project's name (CMakeLists.txt)
constexpr int width = 1280, height = 720;      // pixels

constexpr double hook_speed = 4.0;     // m/s: the hook's speed while an arrow is held
constexpr double hook_reach = 6.0;     // m: the hook stops at x = -6 and x = +6
constexpr double pull_force = 8.0;     // N: down arrow held pulls the claw down
constexpr double swing_impulse = 1.5;  // N*s: each press of Enter swings the claw sideways
constexpr double out_of_level = 0.0;   // m: a ball below this height has fallen out
constexpr double drop_height = 11.0;   // m: balls are dropped again from here
constexpr int exit_usage = 2;          // a mistake on the command line
constexpr int exit_diverged = 4;       // --replay: the recorded states did not come back

// ---- the rules: run after every tick ------------------------------------------------------

/// What the game remembers outside the world. Rules keep their state here (not in globals), so
/// a replay starts it afresh and a rollback can copy it (stateful_rules).
struct Score {
  int caught = 0, missed = 0;
  std::uint32_t dropped = 0;  // balls dropped again so far (picks the next drop's x)
};

bool is_ball(const World& sim, Entity e) {
  return sim.name(e).starts_with("ball");
}

/// Destroys ball `e` and drops a new one like it (the scene's body of the same name) from the
/// top. Destroying and creating, rather than moving the ball, gives it a new handle: the
/// renderer starts a new trail instead of drawing a streak across the screen.
void drop_again(World& sim, Entity e, Score& score, const std::vector<BodyDef>& balls) {
  const std::string name = sim.name(e);
  sim.destroy(e);
  for (const BodyDef& model : balls) {
    if (model.name != name) continue;
    BodyDef ball = model;
    ball.body.position = {-6.0 + double(score.dropped * 5 % 13), drop_height};  // x in -6..6 m
    ball.body.velocity = {};
    sim.create_body(ball);
    ++score.dropped;
    return;
  }
}

/// The game's rules for the level `level`: a ball the claw touched in this tick is caught, a
/// ball below the level is missed; either is dropped again from the top.
TickRules make_rules(Score& score, const WorldDef& level) {
  std::vector<BodyDef> balls;  // the scene's balls, the models of those dropped again
  for (const BodyDef& body : level.bodies) {
    if (body.name.starts_with("ball")) balls.push_back(body);
  }
  return stateful_rules(score, [balls](Score& s, World& sim, const TickInput&) {
    const Entity claw = sim.find("claw");
    std::vector<Entity> caught, missed;
    for (const ContactEvent& contact : sim.contacts_begun()) {  // pairs that began to touch
      if (contact.a == claw && is_ball(sim, contact.b)) caught.push_back(contact.b);
      if (contact.b == claw && is_ball(sim, contact.a)) caught.push_back(contact.a);
    }
    for (std::size_t i = 0; i < sim.body_count(); ++i) {
      const Entity e = sim.entity_at(i);
      if (is_ball(sim, e) && sim.body(e).position.y < out_of_level) missed.push_back(e);
    }
    for (const Entity e : caught) {
      ++s.caught;
      drop_again(sim, e, s, balls);
    }
    for (const Entity e : missed) {
      if (!sim.contains(e)) continue;  // caught in the same tick
      ++s.missed;
      drop_again(sim, e, s, balls);
    }
  });
}

// ---- input: keys or autopilot -> per-body input -------------------------------------------

/// What the player asks for in one frame.
struct Controls {
  int move = 0;        // -1: hook left, +1: hook right, 0: stop
  bool pull = false;   // pull the claw down (as long as it is held)
  bool swing = false;  // swing the claw towards where the hook moves (once)
};

/// The window's keys: arrows left/right move, arrow down pulls, Enter swings.
Controls from_keys(const WindowEvents& ev, const InputSampler& sampler) {
  const std::uint32_t held = sampler.held();  // InputButton bits
  Controls c;
  c.move = ((held & button_right) != 0 ? 1 : 0) - ((held & button_left) != 0 ? 1 : 0);
  c.pull = (held & button_down) != 0;
  for (const WindowEvents::ButtonEdge& edge : ev.edges) {
    if (edge.press && (edge.buttons & button_action) != 0) c.swing = true;
  }
  return c;
}

/// Headless runs play themselves with a fixed pattern of the frame number: the hook sweeps from
/// wall to wall (3 s each way), the claw is pulled down for 0.5 s and swung once every 2 s.
Controls autopilot(std::int64_t frame) {
  return {.move = (frame + 90) / 180 % 2 == 0 ? 1 : -1,
          .pull = frame % 120 >= 90,
          .swing = frame % 120 == 60};
}

/// Turns controls into per-body input for the next ticks, through the sampler (so a recording
/// holds all of it): the hook's velocity (kinematic: it keeps it, so it is sent only when it
/// changes), the pull as a force held every tick, the swing as a one-tick impulse.
struct Player {
  Vec2 hook_velocity{};  // m/s, the last one sent
  int facing = 1;        // +1 right, -1 left: where the hook last moved

  void control(const Controls& c, const World& sim, InputSampler& sampler) {
    const Entity hook = sim.find("hook"), claw = sim.find("claw");
    const double x = sim.body(hook).position.x;  // m
    const bool at_wall = (c.move < 0 && x <= -hook_reach) || (c.move > 0 && x >= hook_reach);
    const Vec2 velocity{at_wall ? 0.0 : c.move * hook_speed, 0.0};
    if (velocity != hook_velocity) sampler.set_velocity(hook, velocity);
    hook_velocity = velocity;
    sampler.set_force(claw, {0.0, c.pull ? -pull_force : 0.0});
    if (c.move != 0) facing = c.move;
    if (c.swing) sampler.apply_impulse(claw, {facing * swing_impulse, 0.0});
  }
};

// ---- the game: a Session with input, rules and an optional recorder ----------------------

SessionSettings view(const Scene& scene) {
  return {.width = width,
          .height = height,
          .title = program,
          .view_center = scene.view.center,  // the scene's [view]
          .view_width = scene.view.width};
}

class Game {
 public:
  /// Builds the level; records into `record_file` unless it is empty.
  Game(const Scene& scene, std::string record_file)
      : session_(world_def(scene), view(scene)),
        rules_(make_rules(score_, session_.definition())),
        scene_file_(scene.file),
        scene_text_(scene.text),
        record_file_(std::move(record_file)) {
    session_.set_show_energy(false);  // the hook and the swings add energy from outside
    for (const std::string& w : session_.simulation().warnings()) {  // the stability guard's
      std::fprintf(stderr, "warning: %s\n", w.c_str());
    }
    if (!record_file_.empty()) start_recording();
  }
  Game(const Game&) = delete;  // the rules hold a reference to score_
  Game& operator=(const Game&) = delete;

  /// One frame of `seconds` (s): each tick steps the world with its input, then the rules run
  /// and the recorder takes the tick.
  void advance(const Controls& controls, double seconds) {
    player_.control(controls, session_.simulation(), sampler_);
    session_.advance_with(seconds, [&](std::uint64_t tick, World& sim) {
      const TickInput input = sampler_.sample(tick);
      sim.step(input);
      rules_.after_tick(sim, input);
      if (recorder_) recorder_->record(input, sim);
    });
  }

  /// Draws the frame with the score under the engine's HUD (and `hint`).
  void draw(const std::string& hint) {
    session_.set_status_lines(
        {"caught " + std::to_string(score_.caught) + "   missed " + std::to_string(score_.missed),
         hint});
    session_.draw();
  }

  /// Back to tick 0 with a new score (and a new recording).
  void restart() {
    session_.restart();
    sampler_ = {};
    player_ = {};
    score_ = {};
    if (recorder_) start_recording();
  }

  /// Prints the score and writes the recording, if any.
  void finish() {
    const World& sim = session_.simulation();
    std::printf("%s: %llu ticks, caught %d, missed %d\n", program,
                static_cast<unsigned long long>(sim.tick()), score_.caught, score_.missed);
    if (!recorder_) return;
    write_recording(record_file_, recorder_->finish(sim));
    std::printf("recorded to %s (check it: %s --replay %s)\n", record_file_.c_str(), program,
                record_file_.c_str());
  }

  Session& session() { return session_; }
  InputSampler& sampler() { return sampler_; }

 private:
  /// A new recording, a state hash every tick, carrying the scene's text: it replays without
  /// the scene file, and editing the file cannot break it.
  void start_recording() { recorder_.emplace(session_.definition(), scene_file_, 1, scene_text_); }

  Session session_;
  InputSampler sampler_;
  Player player_;
  Score score_;
  TickRules rules_;
  std::string scene_file_, scene_text_, record_file_;
  std::optional<Recorder> recorder_;
};

// ---- the three ways to run ----------------------------------------------------------------

/// Plays in a window on the real clock until Esc or the close button.
void play(Game& game) {
  Window window(program, width, height);
  RealClock clock;
  WindowEvents ev;
  for (;;) {
    const auto frame_start = std::chrono::steady_clock::now();
    window.poll(ev);
    if (ev.quit) break;
    apply_loop_keys(ev, game.session().loop());  // space pause, '.' one tick, +/- speed
    if (ev.restart) game.restart();
    feed(ev, game.sampler(), game.session().renderer().camera(), width, height);
    game.advance(from_keys(ev, game.sampler()), clock.frame_seconds());
    game.draw("arrows: move the hook   down: pull   enter: swing   r: restart   esc: quit");
    window.present(game.session().renderer().pixels());
    std::this_thread::sleep_until(frame_start + std::chrono::microseconds(16667));
  }
}

/// Runs `frames` frames headless on a virtual 60 Hz clock (frame 0 is t = 0), the autopilot
/// playing; writes every frame as DIR/frame_NNNNNN.png when `out_dir` is not empty.
void run_headless(Game& game, std::int64_t frames, const std::string& out_dir) {
  std::optional<FrameWriter> writer;
  if (!out_dir.empty()) {
    prepare_output_dir(out_dir);
    writer.emplace(out_dir, width, height);
  }
  const VirtualClock clock(60.0);
  for (std::int64_t frame = 0; frame < frames; ++frame) {
    if (frame > 0) game.advance(autopilot(frame), clock.frame_seconds());
    if (!writer) continue;
    game.draw("autopilot");
    writer->submit(game.session().renderer().pixels());
  }
  if (writer) writer->finish();
}

/// Replays a recording headless through fixstep::replay with this game's rules: 0 when every
/// stored state hash matched, exit_diverged naming the first tick whose state differs.
int replay_file(const std::string& file, const std::optional<std::string>& scene_file) {
  const Recording rec = read_recording(file);  // throws RecordingError
  // The scene the recording carries, unless --scene names another (or it is an old recording).
  WorldDef level =
      world_def(scene_file || rec.scene_text.empty() ? load_scene(scene_file.value_or(rec.scene))
                                                     : parse_scene(rec.scene_text, rec.scene));
  apply_settings(level, rec.settings);  // the recorded dt, integrator, precision, substeps
  Score score;
  const ReplayReport report = replay(level, rec, make_rules(score, level));
  if (const auto& m = report.mismatch) {
    std::fprintf(stderr,
                 "%s: replay of %s diverged at tick %llu: state hash %s recorded, %s replayed "
                 "(the states matched at tick %llu); the recording was edited, or made by a "
                 "build whose physics or rules step differently\n",
                 program, file.c_str(), static_cast<unsigned long long>(m->tick),
                 hex_hash(m->expected).c_str(), hex_hash(m->actual).c_str(),
                 static_cast<unsigned long long>(m->last_match));
    return exit_diverged;
  }
  std::printf("replay: verified %llu hashes over %llu ticks (caught %d, missed %d)\n",
              static_cast<unsigned long long>(report.verified),
              static_cast<unsigned long long>(report.ticks), score.caught, score.missed);
  return 0;
}

// ---- the command line ---------------------------------------------------------------------

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Options {
  std::optional<std::string> scene;  // default: SCENE_FILE, this project's scene.toml
  std::string out, record, replay;
  std::int64_t frames = 0;  // 0: play in a window
};

std::int64_t parse_frames(const std::string& text) {
  std::int64_t n = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), n);
  if (error != std::errc{} || end != text.data() + text.size() || n < 1) {
    throw UsageError("--frames wants a whole number >= 1, got '" + text + "'");
  }
  return n;
}

void print_usage(std::FILE* to) {
  std::fprintf(to,
               "usage: %s [--scene FILE] [--frames N [--out DIR]] [--record FILE]\n"
               "       %s --replay FILE [--scene FILE]\n"
               "(the comment at the top of main.cpp, and README.md, say more)\n",
               program, program);
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; i += 2) {
    const std::string_view flag = argv[i];
    if (i + 1 == argc) throw UsageError(std::string(flag) + " wants a value");
    const std::string value = argv[i + 1];
    if (flag == "--scene")
      o.scene = value;
    else if (flag == "--out")
      o.out = value;
    else if (flag == "--record")
      o.record = value;
    else if (flag == "--replay")
      o.replay = value;
    else if (flag == "--frames")
      o.frames = parse_frames(value);
    else
      throw UsageError("unknown option " + std::string(flag));
  }
  if (!o.out.empty() && o.frames == 0) throw UsageError("--out DIR needs --frames N");
  if (!o.replay.empty() && (!o.out.empty() || !o.record.empty() || o.frames > 0)) {
    throw UsageError("--replay takes no --out, --record or --frames");
  }
  return o;
}

/// Loads the level and prints what the scene loader and the stability guard warn of.
Scene load_level(const std::string& file) {
  Scene scene = load_scene(file);  // throws SceneError naming file:line:column and key
  for (const std::string& w : scene.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  return scene;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    if (argc == 2 && (std::string_view(argv[1]) == "--help" || std::string_view(argv[1]) == "-h")) {
      print_usage(stdout);
      return 0;
    }
    const Options o = parse(argc, argv);
    if (!o.replay.empty()) return replay_file(o.replay, o.scene);
    Game game(load_level(o.scene.value_or(SCENE_FILE)), o.record);
    if (o.frames > 0) {
      run_headless(game, o.frames, o.out);
    } else {
      play(game);
    }
    game.finish();
    return 0;
  } catch (const UsageError& e) {
    std::fprintf(stderr, "%s: %s\n", program, e.what());
    print_usage(stderr);
    return exit_usage;
  } catch (const WindowError& e) {
    std::fprintf(stderr, "%s: error: %s. Run headless instead: %s --frames 120 --out frames\n",
                 program, e.what(), program);
    return 1;
  } catch (const std::exception& e) {  // a bad scene, a bad recording, an unwritable file
    std::fprintf(stderr, "%s: error: %s\n", program, e.what());
    return 1;
  }
}
