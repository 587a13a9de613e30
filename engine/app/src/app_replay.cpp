// fixstep::app: a recording replayed with the game's rules, verified, then drawn; the sync test.
#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <fixstep/capture/capture.hpp>
#include <fixstep/core/input.hpp>
#include <fixstep/core/limits.hpp>
#include <fixstep/core/step_results.hpp>
#include <fixstep/core/stop_request.hpp>
#include <fixstep/core/sync_test.hpp>
#include <fixstep/core/world_settings.hpp>
#include <fixstep/io/command_limits.hpp>
#include <fixstep/io/recording_file.hpp>
#include <fixstep/io/summary.hpp>
#include <optional>

#include "app_modes.hpp"
#include "fixstep/app/game_play.hpp"
#include "game_capture.hpp"

namespace fixstep::app::detail {

namespace {

/// Draws a verified recording through a Session at 60 frames/s of virtual time, its first
/// `ticks` ticks with the game's rules: every o.every-th frame (and the last) into o.out, each
/// named by its frame index (0, K, 2K, ...) and listed with its tick in o.out/frames.csv, the
/// last frame to o.last_frame. A stop request ends it after the frame in progress: the frames
/// written are whole (and listed), the last frame is not written. Returns whether it drew to
/// the end.
bool draw_replay(const Settings& settings, const Level& level, const Recording& rec,
                 std::uint64_t ticks, const Options& o) {
  Session session(level.def, level.view);
  session.set_show_energy(settings.show_energy);
  const std::unique_ptr<AnyGame> game = level.game->clone();
  const TickRules rules = game_rules(*game, settings.rules_before_step);
  rules.attach(session.simulation());
  std::optional<GameCapture> capture;
  if (!o.out.empty()) capture.emplace(o.out, o.overwrite, settings.width, settings.height);
  const VirtualClock clock(virtual_fps);
  TickInput last;
  Overlay overlay;
  for (std::int64_t frame = 0;; ++frame) {
    if (stop_requested() != 0) {
      if (capture) capture->finish();
      return false;
    }
    if (frame > 0) {
      session.advance_with(clock.frame_seconds(), [&](std::uint64_t t, World& world) {
        if (t >= ticks || stop_requested() != 0) return;
        last = rec.input_at(t);
        rules.tick(world, last);
      });
    }
    const std::uint64_t tick = session.simulation().tick();
    const bool end = tick >= ticks;
    const bool write = capture && (frame % o.every == 0 || end);
    // Trails are sampled every tick (Session), so only the frames kept are drawn.
    if (write || (end && !o.last_frame.empty())) {
      session.show_drag(last.pointer, last.drag_body);
      draw_game(session, *game, overlay, {});
    }
    if (write) capture->add(static_cast<std::uint64_t>(frame), session);
    if (end) break;
  }
  if (!o.last_frame.empty()) {
    write_png(o.last_frame, settings.width, settings.height, session.renderer().pixels());
  }
  if (capture) capture->finish();
  return true;
}

}  // namespace

int replay_file(const AnyGame& prototype, const Settings& settings, const Options& o) {
  const Recording rec = read_recording(o.replay);  // throws RecordingError naming the file
  // A recording from before rules were named (format 3) is replayed: its hashes decide.
  const std::string rules = rules_name_of(settings.name);
  if (!rec.rules_name.empty() &&
      (rec.rules_name != rules || rec.rules_version != settings.rules_version)) {
    std::fprintf(stderr,
                 "%s: error: %s needs the rules %s version %u, and this program has %s version "
                 "%u: replay it with the program (and version) that recorded it\n",
                 settings.name.c_str(), o.replay.c_str(), rec.rules_name.c_str(), rec.rules_version,
                 rules.c_str(), settings.rules_version);
    return exit_error;
  }
  const GameReplay r = replay_game(prototype, settings, rec, o.replay, o.scene);
  const ReplayReport& report = r.report;
  // Only a recording that verified is drawn: a diverging one leaves no frame behind.
  if (report.ok() && (!o.out.empty() || !o.last_frame.empty()) &&
      !draw_replay(settings, r.level, rec, report.ticks, o)) {
    return stopped(settings, report.ticks, false,
                   "verified; the frames drawn before the stop written, no --last-frame");
  }
  std::printf("%s\n", summary_line(*r.world, r.initial_energy).c_str());
  if (const std::string s = r.game->summary(); !s.empty()) std::printf("%s\n", s.c_str());
  std::printf("verified=%llu\n", static_cast<unsigned long long>(report.verified));
  if (const auto& m = report.mismatch) {
    std::fprintf(stderr,
                 "%s: error: %s diverged at tick %llu: state_hash %s recorded, %s replayed "
                 "(the states matched at tick %llu); the recording was edited, or made by a "
                 "build whose physics or rules step differently%s\n",
                 settings.name.c_str(), o.replay.c_str(), static_cast<unsigned long long>(m->tick),
                 hex_hash(m->expected).c_str(), hex_hash(m->actual).c_str(),
                 static_cast<unsigned long long>(m->last_match),
                 o.out.empty() && o.last_frame.empty() ? "" : "; no frame was written");
    return exit_diverged;
  }
  return 0;
}

int sync_test(const AnyGame& prototype, const Settings& settings, const Options& o) {
  const Level level = load_level(prototype, settings, o.scene.value_or(settings.scene_file));
  check_frames_work(level, o.frames, 1 + static_cast<std::uint64_t>(o.sync_test),
                    fmt::format("--frames {} with --sync-test {} (every tick re-simulates {} more)",
                                o.frames, o.sync_test, o.sync_test));
  World world(level.def);
  check_sync_test_memory(world, o.sync_test);
  const double initial_energy = world.energy().total();
  const std::unique_ptr<AnyGame> game = level.game->clone();
  SyncTest test(world, o.sync_test, game_rules(*game, settings.rules_before_step));
  InputSampler sampler;
  std::optional<InputScript> script;
  if (!o.input.empty()) script = game_script(settings, level, o.input);
  std::optional<ScriptPlayer> player;
  if (script) player.emplace(*script);
  FixedStepLoop loop(world);
  const VirtualClock clock(virtual_fps);
  bool torn = false;  // a stop request abandoned a tick half-way
  for (std::int64_t frame = 1; frame < o.frames && !test.mismatch() && stop_requested() == 0;
       ++frame) {
    if (!player) game->autopilot(frame, world, sampler);
    try {
      loop.advance_with(clock.frame_seconds(), [&](std::uint64_t t) {
        if (test.mismatch() || stop_requested() != 0) return;
        if (player) player->feed(t, sampler);
        TickInput input = sampler.sample(t);
        game->prepare(input, world);
        test.step(input);
      });
    } catch (const StopRequested&) {
      torn = true;
      break;
    }
  }
  if (const auto& m = test.mismatch()) {
    std::fprintf(stderr,
                 "%s: error: sync test: tick %llu re-simulated differs: state_hash %s first, %s "
                 "after a rollback of %d ticks%s; a state the snapshot or the game's copy "
                 "misses, or a rule that is not deterministic\n",
                 settings.name.c_str(), static_cast<unsigned long long>(m->tick),
                 hex_hash(m->expected).c_str(), hex_hash(m->actual).c_str(), o.sync_test,
                 m->dissipated_differs ? " (the dissipated energy differs)" : "");
    return exit_sync_mismatch;
  }
  if (stop_requested() != 0) {
    return stopped(settings, world.tick(), torn, "every tick before it the same after a rollback");
  }
  std::printf("%s\n", summary_line(world, initial_energy).c_str());
  if (const std::string s = game->summary(); !s.empty()) std::printf("%s\n", s.c_str());
  std::printf(
      "sync test: %llu ticks, each rolled back %d ticks and re-simulated (%llu ticks): "
      "the same\n",
      static_cast<unsigned long long>(world.tick()), o.sync_test,
      static_cast<unsigned long long>(test.resimulated()));
  return 0;
}

}  // namespace fixstep::app::detail
