// A fixstep prototype, written by `fixstep new`: a hook slides along the top, a rope hangs from
// it with a claw at its end, and balls fall from the sky. Catch them with the claw.
//
// The game is the type below: setup() takes the level (scene.toml) and keeps the handles of
// its bodies; rules() runs before every tick's step (input -> rules -> step: live, in a replay
// and in the sync test alike) and turns the tick's actions into motion; autopilot() presses
// actions in a headless run; draw() adds the score to the HUD. fixstep::app::run does the
// rest: the window, the keys, headless frames, --input, --record, --replay, --sync-test, --help.
#include <algorithm>
#include <cstdint>
#include <fixstep/app.hpp>   // fixstep::app: app::run and what a game draws with
#include <fixstep/core.hpp>  // fixstep::core: the world, its bodies and their input
#include <string>
#include <vector>

namespace {

using namespace fixstep;

// The game's actions: bits of TickInput::held / pressed, bound to keys in main().
constexpr std::uint32_t act_left = 1u << 0, act_right = 1u << 1, act_pull = 1u << 2,
                        act_swing = 1u << 3;

constexpr double hook_speed = 4.0;    // m/s: the hook's speed while left or right is held
constexpr double hook_reach = 6.0;    // m: the hook stops at x = -6 and x = +6
constexpr double pull_accel = 8.0;    // m/s^2: pull held draws the claw down
constexpr double swing_speed = 1.5;   // m/s: each press of swing throws the claw sideways
constexpr double out_of_level = 0.0;  // m: a ball below this height has fallen out
constexpr double drop_height = 11.0;  // m: balls are dropped again from here

struct Catch {
  // What the game remembers outside the world; run() copies it to restart or roll back.
  int caught = 0, missed = 0;
  std::vector<BodyDef> balls;  // the level's balls: the models of those dropped again
  Entity hook{}, claw{};       // never destroyed: their handles hold for the whole game

  void setup(WorldDef& level) {
    hook = level.find_body("hook"), claw = level.find_body("claw");
    for (BodyDef& body : level.bodies) {  // a ball carries 1 + its place in `balls`
      if (body.name.starts_with("ball")) body.user_data = balls.size() + 1, balls.push_back(body);
    }
  }

  void rules(World& world, const TickInput& in) {
    const double dt = world.settings().dt;
    const int move = int((in.held & act_right) != 0) - int((in.held & act_left) != 0);
    const double x = world.body(hook).position.x;
    const bool at_wall = (move < 0 && x <= -hook_reach) || (move > 0 && x >= hook_reach);
    world.set_velocity(hook, {at_wall ? 0.0 : move * hook_speed, 0.0});
    Vec2 v = world.body(claw).velocity;
    if (in.held & act_pull) v.y -= pull_accel * dt;
    if (in.pressed & act_swing) v.x += (move < 0 ? -1 : 1) * swing_speed;
    world.set_velocity(claw, v);
    // The last tick's catches (contacts that began) and misses: each ball dropped again.
    std::vector<Entity> gone;
    for (const ContactEvent& c : world.contacts_begun()) {
      const Entity ball = c.a == claw ? c.b : (c.b == claw ? c.a : null_entity);
      if (world.user_data(ball) != 0) ++caught, gone.push_back(ball);
    }
    for (const Entity e : world.bodies()) {
      if (world.user_data(e) == 0 || world.body(e).position.y >= out_of_level) continue;
      if (std::find(gone.begin(), gone.end(), e) == gone.end()) ++missed, gone.push_back(e);
    }
    for (const Entity e : gone) drop_again(world, e);
  }

  // At an x the world's random generator picks: its state is in every snapshot, so replays and
  // rollbacks drop the same balls ([world] seed in scene.toml chooses the sequence).
  void drop_again(World& world, Entity e) {
    BodyDef ball = balls[world.user_data(e) - 1];  // the model, its user data included
    world.destroy(e);
    ball.body.position = {world.random().uniform(-hook_reach, hook_reach), drop_height};
    ball.body.velocity = {};
    world.create_body(ball);
  }

  // Headless runs press actions in a pattern: the hook sweeps from wall to wall (3 s each way),
  // pull for 0.5 s and swing once every 2 s.
  void autopilot(std::int64_t frame, const World&, InputSampler& sampler) const {
    const bool right = (frame + 90) / 180 % 2 == 0, pull = frame % 120 >= 90;
    sampler.release(act_left | act_right | (pull ? 0 : act_pull) | act_swing);
    sampler.press((right ? act_right : act_left) | (pull ? act_pull : 0) |
                  (frame % 120 == 60 ? act_swing : 0));
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
                   .controls = "a/d: move the hook   s: pull   space: swing",
                   .actions = {{"left", act_left, {Key::a, Key::left, Key::pad_left}},
                               {"right", act_right, {Key::d, Key::right, Key::pad_right}},
                               {"pull", act_pull, {Key::s, Key::down, Key::pad_down}},
                               {"swing", act_swing, {Key::space, Key::enter, Key::pad_a}}},
                   .loop_keys = {{LoopAction::pause, {Key::p}},  // space swings
                                 {LoopAction::step, {Key::period}},
                                 {LoopAction::restart, {Key::r}},
                                 {LoopAction::quit, {Key::escape}}},
                   .rules_before_step = true},
                  argc, argv);
}
