// A fixstep prototype, written by `fixstep new`: walk and jump to catch the crates that fall
// from the sky before they land; a seesaw on a hinge tosses them about.
//
// The game is the type below: setup() takes the level (scene.toml) and keeps the handles of
// its bodies; rules() runs before every tick's step (input -> rules -> step: live, in a replay
// and in the sync test alike) and turns the tick's actions into the catcher's motion;
// autopilot() plays in a headless run; draw() adds the score to the HUD. fixstep::app::run does
// the rest: the window, the keys, headless frames, --input, --record, --replay, --sync-test.
#include <algorithm>
#include <cstdint>
#include <fixstep/app.hpp>   // fixstep::app: app::run and what a game draws with
#include <fixstep/core.hpp>  // fixstep::core: the world, its bodies, movers and joints
#include <string>
#include <vector>

namespace {

using namespace fixstep;

constexpr std::uint32_t act_jump = 1u << 0;  // the game's action (a bit of TickInput::held)
constexpr std::size_t walk_axis = 0;         // its axis (TickInput::axes): -1 left, +1 right

constexpr double walk_speed = 5.0;    // m/s at a full walk
constexpr double jump_speed = 7.0;    // m/s: a jump of v^2 / 2g = 2.5 m
constexpr double gravity = 9.81;      // m/s^2: the catcher's, added while it is in the air
constexpr double reach = 0.9;         // m: a crate this close to the catcher's centre is caught
constexpr double landed = 0.45;       // m: a crate whose centre is this low has landed: missed
constexpr double drop_height = 11.0;  // m: crates are dropped again from here

struct Catch {
  // What the game remembers outside the world; run() copies it to restart or roll back.
  int caught = 0, missed = 0;
  std::vector<BodyDef> crates;  // the level's crates: the models of those dropped again
  Entity catcher{};             // never destroyed: its handle holds for the whole game

  void setup(WorldDef& level) {
    catcher = level.find_body("catcher");
    for (BodyDef& body : level.bodies) {  // a crate carries 1 + its place in `crates`
      if (body.name.starts_with("crate"))
        body.user_data = crates.size() + 1, crates.push_back(body);
    }
  }

  void rules(World& world, const TickInput& in) {
    // The catcher is a character mover (scene.toml: mover = {...}): the world slides it at the
    // velocity it wants, over the floor and the seesaw; gravity and jumps are the game's.
    const MoverState& m = world.mover_state(catcher);
    Vec2 v{in.axes[walk_axis] * walk_speed, m.velocity.y};
    if (m.on_floor && (in.pressed & act_jump) != 0) v.y = jump_speed;
    if (!m.on_floor) v.y -= gravity * world.settings().dt;
    world.set_velocity(catcher, v);
    // Crates within reach are caught, crates on the ground missed: each dropped again.
    const Vec2 at = world.body(catcher).position;
    for (const Entity e : world.bodies()) {
      if (world.user_data(e) == 0) continue;
      const Vec2 d = world.body(e).position - at;
      const bool near = d.x * d.x + d.y * d.y < reach * reach;
      if (near || world.body(e).position.y < landed) {
        ++(near ? caught : missed);
        drop_again(world, e);
        return;  // bodies() changed: the next crate next tick
      }
    }
  }

  // At an x the world's random generator picks: its state is in every snapshot, so replays and
  // rollbacks drop the same crates ([world] seed in scene.toml chooses the sequence).
  void drop_again(World& world, Entity e) {
    BodyDef crate = crates[world.user_data(e) - 1];  // the model, its user data included
    world.destroy(e);
    crate.body.position = {world.random().uniform(-6.0, 6.0), drop_height};
    world.create_body(crate);
  }

  // Headless runs walk back and forth (4 s each way) and jump every 1.5 s.
  void autopilot(std::int64_t frame, const World&, InputSampler& sampler) const {
    sampler.set_axis(walk_axis, (frame / 240) % 2 == 0 ? 1.0 : -1.0);
    frame % 90 == 0 ? sampler.press(act_jump) : sampler.release(act_jump);
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
  return app::run(
      Catch{},
      {.name = PROGRAM_NAME,  // the project's name (CMakeLists.txt)
       .description = "catch the falling crates",
       .scene_file = SCENE_FILE,  // this project's scene.toml
       .controls = "a/d: walk   space: jump",
       .actions = {{"jump", act_jump, {Key::space, Key::w, Key::up, Key::pad_a}}},
       .axes = {{"walk", walk_axis, {Key::a, Key::left}, {Key::d, Key::right}, PadAxis::left_x}},
       .loop_keys = {{LoopAction::pause, {Key::p}},  // space jumps
                     {LoopAction::step, {Key::period}},
                     {LoopAction::restart, {Key::r}},
                     {LoopAction::quit, {Key::escape}}},
       .rules_before_step = true},
      argc, argv);
}
