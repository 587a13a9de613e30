// A fixstep prototype, written by `fixstep new`: a hook slides along the top, a rope hangs from
// it with a claw at its end, and balls fall from the sky. Catch them with the claw.
//
// The game is the type below: setup() takes the level (scene.toml), rules() runs after every
// tick (live, in a replay and in the sync test alike), input() and autopilot() turn keys or a
// headless pattern into per-body input, draw() adds the score to the HUD. fixstep::app::run
// does the rest: the window, headless frames, --record, --replay, --sync-test and --help.
#include <algorithm>
#include <cstdint>
#include <fixstep/app.hpp>   // fixstep::app: app::run and what a game draws with
#include <fixstep/core.hpp>  // fixstep::core: the world, its bodies and their input
#include <string>
#include <vector>

namespace {

using namespace fixstep;

constexpr double hook_speed = 4.0;     // m/s: the hook's speed while an arrow is held
constexpr double hook_reach = 6.0;     // m: the hook stops at x = -6 and x = +6
constexpr double pull_force = 8.0;     // N: down arrow held pulls the claw down
constexpr double swing_impulse = 1.5;  // N*s: each press of Enter swings the claw sideways
constexpr double out_of_level = 0.0;   // m: a ball below this height has fallen out
constexpr double drop_height = 11.0;   // m: balls are dropped again from here

struct Catch {
  // What the game remembers outside the world; run() copies it to restart or roll back.
  int caught = 0, missed = 0;
  std::vector<BodyDef> balls;  // the level's balls: the models of those dropped again
  Vec2 hook_velocity{};        // m/s, the last one sent
  int facing = 1;              // +1 right, -1 left: where the hook last moved

  // The level's bodies are told apart by their user data (BodyDef::user_data, kept with each
  // body, copied by snapshots): a ball carries 1 + its place in `balls`, the claw `claw_tag`.
  // The scene names them; setup() reads the names once, the rules never.
  static constexpr std::uint64_t claw_tag = 1'000'000;

  void setup(WorldDef& level) {
    for (BodyDef& body : level.bodies) {
      if (body.name.starts_with("ball")) {
        body.user_data = balls.size() + 1;
        balls.push_back(body);
      } else if (body.name == "claw") {
        body.user_data = claw_tag;
      }
    }
  }
  static bool is_ball(const World& world, Entity e) {
    const std::uint64_t tag = world.user_data(e);
    return tag >= 1 && tag < claw_tag;
  }

  // A ball the claw touched in this tick is caught, a ball below the level is missed; either
  // is destroyed and dropped again from the top (a new handle: a new trail, not a streak), at
  // an x the world's random generator picks (its state is in every snapshot, so replays and
  // rollbacks drop the same balls; [world] seed in scene.toml chooses the sequence).
  void rules(World& world, const TickInput&) {
    std::vector<Entity> gone;
    for (const ContactEvent& c : world.contacts_begun()) {  // pairs that began to touch
      const bool a_is_claw = world.user_data(c.a) == claw_tag;
      const Entity ball = a_is_claw ? c.b : (world.user_data(c.b) == claw_tag ? c.a : null_entity);
      if (ball != null_entity && is_ball(world, ball)) ++caught, gone.push_back(ball);
    }
    for (const Entity e : world.bodies()) {
      if (!is_ball(world, e) || world.body(e).position.y >= out_of_level) continue;
      if (std::find(gone.begin(), gone.end(), e) == gone.end()) ++missed, gone.push_back(e);
    }
    for (const Entity e : gone) drop_again(world, e);
  }

  void drop_again(World& world, Entity e) {
    BodyDef ball = balls[world.user_data(e) - 1];  // the model, its user data included
    world.destroy(e);
    ball.body.position = {world.random().uniform(-hook_reach, hook_reach), drop_height};
    ball.body.velocity = {};
    world.create_body(ball);
  }

  // The window's keys: arrows left/right move the hook, down pulls the claw, Enter swings it.
  void input(const UserEvents& ev, const World& world, InputSampler& sampler) const {
    const std::uint32_t held = sampler.held();
    bool swing = false;
    for (const UserEvents::ButtonEdge& edge : ev.edges) {
      swing = swing || (edge.press && (edge.buttons & button_action) != 0);
    }
    control(int(held & button_right ? 1 : 0) - int(held & button_left ? 1 : 0),
            (held & button_down) != 0, swing, world, sampler);
  }

  // Headless runs play a fixed pattern: the hook sweeps from wall to wall (3 s each way), the
  // claw is pulled down for 0.5 s and swung once every 2 s.
  void autopilot(std::int64_t frame, const World& world, InputSampler& sampler) const {
    control((frame + 90) / 180 % 2 == 0 ? 1 : -1, frame % 120 >= 90, frame % 120 == 60, world,
            sampler);
  }

  // Per-body input through the sampler (so a recording holds it): the hook's velocity
  // (kinematic: sent when it changes), the pull as a held force, the swing as an impulse
  // towards where the hook moves (right when it stands).
  void control(int move, bool pull, bool swing, const World& world, InputSampler& sampler) const {
    const Entity hook = world.find("hook"), claw = world.find("claw");
    const Body now = world.body(hook);
    const bool at_wall =
        (move < 0 && now.position.x <= -hook_reach) || (move > 0 && now.position.x >= hook_reach);
    const Vec2 velocity{at_wall ? 0.0 : move * hook_speed, 0.0};  // m/s
    if (velocity != now.velocity) sampler.set_velocity(hook, velocity);
    sampler.set_force(claw, {0.0, pull ? -pull_force : 0.0});
    if (swing) sampler.apply_impulse(claw, {(move < 0 ? -1 : 1) * swing_impulse, 0.0});
  }

  void draw(app::Overlay& overlay) const {
    overlay.text("caught " + std::to_string(caught) + "   missed " + std::to_string(missed));
  }
  std::string summary() const {
    return "caught=" + std::to_string(caught) + " missed=" + std::to_string(missed);
  }
};

}  // namespace

int main(int argc, char** argv) {
  return app::run(Catch{},
                  {.name = PROGRAM_NAME,  // the project's name (CMakeLists.txt)
                   .description = "catch the falling balls with the claw",
                   .scene_file = SCENE_FILE,  // this project's scene.toml
                   .controls = "arrows: move the hook   down: pull   enter: swing"},
                  argc, argv);
}
