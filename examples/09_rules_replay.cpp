// Rules in replay: a world with a rule run after every tick (a ball that rolls off the right
// edge is put back at the top left, and counted) is recorded with its input, then replayed
// through the library with the rules (fixstep::replay) and every state hash verified; the same
// recording replayed without them diverges. Draws the last frame of a replay.
//
//   09_rules_replay [OUT.png]
#include <cmath>
#include <cstdio>
#include <exception>
#include <fixstep/capture.hpp>
#include <fixstep/recording.hpp>
#include <fixstep/recording_file.hpp>
#include <fixstep/rules.hpp>
#include <fixstep/session.hpp>
#include <span>
#include <string>

namespace {

using namespace fixstep;

constexpr std::uint64_t ticks = 720;  // 6 s at 120 ticks/s
constexpr double edge = 8.5;          // m: past it a ball has fallen off
const Vec2 respawn{-7.0, 5.0};        // m

WorldDef world() {
  WorldDef def;
  def.settings = {.dt = 1.0 / 120.0, .integrator = Integrator::semi_implicit_euler};
  def.settings.contacts = ContactSettings{.restitution = 0.6, .friction = 0.0};
  const Rgba8 colors[3] = {{230, 70, 60, 255}, {250, 200, 60, 255}, {90, 160, 230, 255}};
  for (int i = 0; i < 3; ++i) {
    BodyDef b;
    b.name = "ball" + std::to_string(i);
    b.body = Body{.mass = 1.0, .position = {-6.0 + 2.5 * i, 3.0 + i}, .velocity = {}};
    b.gravity = Gravity{};
    b.collider = Collider{.radius = 0.4};
    b.appearance = Appearance{.radius = 0.4, .color = colors[i]};
    def.bodies.push_back(b);
  }
  // A slope falling to the right: n = (0.25, 1) normalised, through (0, 0).
  def.planes.push_back({.normal = {0.25, 1.0}, .offset = 0, .restitution = 0.3, .friction = 0.1});
  return def;
}

// The rule's state: how many balls fell off (kept outside the world, so saved and restored).
struct Game {
  int respawns = 0;
};

TickRules rules(Game& game) {
  return stateful_rules(game, [](Game& g, World& sim, const TickInput&) {
    for (std::size_t i = 0; i < sim.body_count(); ++i) {
      const Entity e = sim.bodies()[i];
      if (sim.body(e).position.x <= edge) continue;
      sim.set_body(e, Body{.mass = 1.0, .position = respawn, .velocity = {}});
      ++g.respawns;
    }
  });
}

// The player: an upward kick (impulse, N·s) for one of the three balls every 1.5 s.
TickInput input_of(std::uint64_t t, std::span<const Entity> balls) {
  TickInput in{.tick = t};
  if (t % 180 == 90) in.bodies.push_back({balls[t / 180 % 3], BodyInputKind::impulse, {1.0, 5.0}});
  return in;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string png = argc > 1 ? argv[1] : "09_rules_replay.png";
  try {
    const WorldDef def = world();
    // Live: step, then the rules, recording each tick's input and state hash.
    Game live;
    const TickRules live_rules = rules(live);
    World sim = World(def);
    Recorder recorder(def, "09_rules_replay (built in code)", 1);
    for (std::uint64_t t = 0; t < ticks; ++t) {
      const TickInput in = input_of(t, sim.defined_bodies());  // def.bodies' handles, in order
      sim.step(in);
      live_rules.after_tick(sim, in);
      recorder.record(in, sim);
    }
    const Recording rec = recorder.finish(sim);

    // Replayed with the rules (from a fresh state): every hash matches.
    Game replayed;
    const ReplayReport with = replay(def, rec, rules(replayed));
    const ReplayReport without = replay(def, rec);
    if (!with.ok() || replayed.respawns != live.respawns || without.ok()) {
      std::fprintf(stderr, "09_rules_replay: the replay with the rules did not verify\n");
      return 1;
    }

    // Draw the replay through a Session, with the rules, to its last tick.
    Session session(def, SessionSettings{.width = 640,
                                         .height = 360,
                                         .title = "rules in replay",
                                         .view_center = Vec2{0.0, 1.5},
                                         .view_width = 19.0});
    session.set_show_engine_hud(false);  // the status lines only
    Game drawn;
    const TickRules draw_rules = rules(drawn);
    const VirtualClock clock(60.0);
    while (session.simulation().tick() < ticks) {
      session.advance_with(clock.frame_seconds(), [&](std::uint64_t t, World& s) {
        s.step(rec.input_at(t));
        draw_rules.after_tick(s, rec.input_at(t));
      });
      session.set_status_lines(
          {"respawns: " + std::to_string(drawn.respawns) + " (live " +
               std::to_string(live.respawns) + ")",
           "replay with the rules: " + std::to_string(with.verified) + " hashes verified",
           "without them: diverged at tick " + std::to_string(without.mismatch->tick)});
      session.draw();
    }
    write_png(png, 640, 360, session.renderer().pixels());
    std::printf("respawns=%d verified=%llu without_rules_diverged_at=%llu\nwrote %s\n",
                live.respawns, static_cast<unsigned long long>(with.verified),
                static_cast<unsigned long long>(without.mismatch->tick), png.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "09_rules_replay: %s\n", e.what());
    return 1;
  }
  return 0;
}
