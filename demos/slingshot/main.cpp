// slingshot: play the game in a window, record a session, or replay one headless.
//
//   slingshot [--record FILE] [--frames N]      play (mouse: drag the ball; r restart; esc quit)
//   slingshot --replay FILE [--out DIR [--every K]] [--last-frame PNG]
//
// Every tick of play runs the same four steps, live or replayed:
//   input  = the mouse, sampled for this tick (InputSampler), or the recording's input
//   prepare_input: the pointer may drag only the loaded ball (live only: the recording holds
//                  the prepared input, drag_body included)
//   step   = sim.step(input): physics, with the pointer's drag spring
//   rules  = after_tick(): cut the band, score the hits (sim.impacts()), knock targets off, reload
// so a replay of the recorded inputs with the rules (fixstep::replay(sim, rec,
// slingshot::rules(game))) reproduces the game, and its state hashes, bit for bit.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fixstep/capture.hpp>
#include <fixstep/pointer_drag.hpp>
#include <fixstep/recording.hpp>
#include <fixstep/session.hpp>
#include <fixstep/window.hpp>
#include <optional>
#include <string>
#include <thread>

#include "fixstep/recording_file.hpp"
#include "fixstep/summary.hpp"
#include "game.hpp"

namespace {

using namespace fixstep;

constexpr int width = 1280, height = 720;  // pixels
constexpr const char* scene_name = "demos/slingshot (built in code)";
// A recording stores the state hash after every tick, so a replay names the exact first tick
// that differs (about 25 bytes a tick).
constexpr std::uint64_t hash_every = 1;

// The camera: the whole level, ground near the bottom, 46 m wide (walls at the edges).
SessionSettings view() {
  return {.width = width,
          .height = height,
          .title = "slingshot",
          .view_center = Vec2{0.0, 9.0},
          .view_width = 46.0};
}

// Plays in a window on the real clock; records to `record_file` when it is not empty.
int play(const std::string& record_file, std::int64_t frames) {
  Window window("fixstep - slingshot", width, height);
  Session session(slingshot::make_level(), view());
  session.set_show_energy(false);  // the pull and the rules add energy from outside the world
  slingshot::GameState game;
  InputSampler sampler;
  PointerDrag drag(0.3);  // m: a small ball is easy to grab
  std::optional<Recorder> recorder;
  if (!record_file.empty()) recorder.emplace(session.definition(), scene_name, hash_every);

  RealClock clock;
  WindowEvents ev;
  TickInput last;  // the input of the last tick run (drawn: the drag)
  for (std::int64_t frame = 0; frames == 0 || frame < frames; ++frame) {
    const auto frame_start = std::chrono::steady_clock::now();
    window.poll(ev);
    if (ev.quit) break;
    apply_loop_keys(ev, session.loop());
    feed(ev, sampler, session.renderer().camera(), width, height);
    if (ev.restart) {  // a new game (and a new recording)
      session.restart();
      game = {};
      drag.reset();
      last = {};
      if (recorder) recorder.emplace(session.definition(), scene_name, hash_every);
    }
    session.advance_with(clock.frame_seconds(), [&](std::uint64_t t, World& sim) {
      TickInput in = sampler.sample(t);
      slingshot::prepare_input(game, drag, in, sim);
      slingshot::play_tick(game, in, sim);
      if (recorder) recorder->record(in, sim);
      last = in;
    });
    session.show_drag(last.pointer, last.drag_body);  // the pointer's spring to the ball
    session.set_status_lines(slingshot::status_lines(game));
    session.draw();
    window.present(session.renderer().pixels());
    std::this_thread::sleep_until(frame_start + std::chrono::microseconds(16667));
  }
  const World& sim = session.simulation();
  std::printf("%s\n%s\n", summary_line(sim, session.initial_energy()).c_str(),
              slingshot::describe(game).c_str());
  if (recorder) {
    write_recording(record_file, recorder->finish(sim));
    std::printf("recorded %llu ticks to %s\n", static_cast<unsigned long long>(sim.tick()),
                record_file.c_str());
  }
  return 0;
}

// Draws a recorded game through a Session at 60 frames/s of virtual time, its first `ticks`
// ticks with the game's rules: every `every`-th frame (and the last) into out_dir, the last
// frame to last_frame. Checks nothing: replay_file verifies the recording first.
void draw_replay(const Recording& rec, std::uint64_t ticks, const std::string& out_dir, int every,
                 const std::string& last_frame) {
  Session session(slingshot::make_level(), view());
  session.set_show_energy(false);  // the pull and the rules add energy from outside the world
  slingshot::GameState game;
  const TickRules rules = slingshot::rules(game);
  std::optional<FrameWriter> writer;
  if (!out_dir.empty()) {
    prepare_output_dir(out_dir);
    writer.emplace(out_dir, width, height);
  }
  const VirtualClock clock(60.0);
  TickInput last;
  for (std::int64_t frame = 0;; ++frame) {
    if (frame > 0) {
      session.advance_with(clock.frame_seconds(), [&](std::uint64_t t, World& sim) {
        if (t >= ticks) return;
        last = rec.input_at(t);
        sim.step(last);
        rules.after_tick(sim, last);
      });
    }
    const std::uint64_t tick = session.simulation().tick();
    const bool end = tick >= ticks;
    const bool write = writer && (frame % every == 0 || end);
    // Trails grow by one sample per frame drawn: the trail_frames frames before each frame
    // written are drawn too, so its trails look as they do in the window.
    const double frames_left = double(ticks - std::min(tick, ticks)) * slingshot::dt * 60;
    const bool warm_up = (writer && every - frame % every <= Renderer::trail_frames) ||
                         (!last_frame.empty() && frames_left <= Renderer::trail_frames + 1);
    if (write || warm_up || (end && !last_frame.empty())) {
      session.show_drag(last.pointer, last.drag_body);
      session.set_status_lines(slingshot::status_lines(game));
      session.draw();
    }
    if (write) writer->submit(session.renderer().pixels());
    if (end) break;
  }
  if (!last_frame.empty()) write_png(last_frame, width, height, session.renderer().pixels());
  if (writer) writer->finish();
}

// Replays a recording headless with the game's rules (fixstep::replay), checking every stored
// hash; then draws it (draw_replay) when out_dir or last_frame is given.
int replay_file(const std::string& file, const std::string& out_dir, int every,
                const std::string& last_frame) {
  const Recording rec = read_recording(file);
  const WorldDef level = slingshot::make_level();
  if (definition_hash(level) != rec.definition_hash) {
    std::fprintf(stderr, "slingshot: error: %s was recorded on another level (hash %s, not %s)\n",
                 file.c_str(), hex_hash(rec.definition_hash).c_str(),
                 hex_hash(definition_hash(level)).c_str());
    return 5;
  }
  World sim = World(level);
  const double initial_energy = sim.energy().total();
  slingshot::GameState game;
  const ReplayReport report = replay(sim, rec, slingshot::rules(game));
  // Only a recording that verified is drawn: a diverging one leaves no frame behind.
  if (report.ok() && (!out_dir.empty() || !last_frame.empty())) {
    draw_replay(rec, report.ticks, out_dir, every, last_frame);
  }
  std::printf("%s\n%s\nverified=%llu\n", summary_line(sim, initial_energy).c_str(),
              slingshot::describe(game).c_str(), static_cast<unsigned long long>(report.verified));
  if (const auto& m = report.mismatch) {
    std::fprintf(stderr,
                 "slingshot: error: %s diverged at tick %llu: state_hash %s recorded, %s replayed "
                 "(the states matched at tick %llu); the recording was edited, or made by a "
                 "build whose physics or rules step differently%s\n",
                 file.c_str(), static_cast<unsigned long long>(m->tick),
                 hex_hash(m->expected).c_str(), hex_hash(m->actual).c_str(),
                 static_cast<unsigned long long>(m->last_match),
                 out_dir.empty() && last_frame.empty() ? "" : "; no frame was written");
    return 4;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    CLI::App app("slingshot: drag the red ball back, let go, knock the targets off their ropes");
    std::string record, replay, out_dir, last_frame;
    std::int64_t frames = 0;
    int every = 1;
    auto* record_opt = app.add_option("--record", record, "play and record the session into FILE");
    app.add_option("--frames", frames, "quit the window after N frames")
        ->check(CLI::NonNegativeNumber);
    auto* replay_opt =
        app.add_option("--replay", replay, "replay FILE headless, checking its hashes");
    app.add_option("--out", out_dir, "with --replay: write frames as PNG into DIR")
        ->needs(replay_opt);
    app.add_option("--every", every, "with --out: every K-th frame (and the last)")
        ->check(CLI::PositiveNumber);
    app.add_option("--last-frame", last_frame, "with --replay: write the last frame as PNG")
        ->needs(replay_opt);
    replay_opt->excludes(record_opt);
    CLI11_PARSE(app, argc, argv);
    if (!replay.empty()) return replay_file(replay, out_dir, every, last_frame);
    return play(record, frames);
  } catch (const WindowError& e) {
    std::fprintf(stderr, "slingshot: error: %s. Replay a game headless instead: --replay FILE\n",
                 e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "slingshot: error: %s\n", e.what());
    return 1;
  }
}
