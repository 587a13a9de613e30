// A single-player game made networked. King of the hill: each player pushes its own disc with
// the arrow keys, and scores a point a tick while its disc alone is in the ring. Written for
// fixstep::app::run, it becomes a two-player game over the network with three changes:
//   1. main() calls fixstep::net::run instead of app::run (link fixstep::net_app): the program
//      gets --host PORT and --join HOST:PORT (and --session lockstep|rollback, --record, ...);
//   2. seat(player): which player this program plays (its input and its bot);
//   3. merge(players, world): the tick's one input from every player's, run on every peer
//      inside the tick (deterministic, like the rules): player i's arrows push disc i.
// The rules and their state are unchanged: every peer runs them after each tick, and a match's
// recording replays with them (--replay) like a single-player one.
//
//   11_networked_game --host 7777                     player 0 (in a window)
//   11_networked_game --join 127.0.0.1:7777           player 1
//   11_networked_game --host 0 --bot --ticks 240 --record a.rec     scripted, headless
//   11_networked_game --replay a.rec                  verify the match's recording
#include <array>
#include <fixstep/net_app.hpp>
#include <span>
#include <string>

namespace {

using namespace fixstep;

constexpr double ring = 2.0;    // m, the ring's radius
constexpr double thrust = 6.0;  // N, the arrows' force on a 1 kg disc
constexpr std::array<const char*, 2> names{"red", "blue"};

/// Player `i`'s held arrows as a force on its disc, N.
BodyInput push(int i, const TickInput& in, const World& world) {
  const auto held = [&](std::uint32_t b) { return (in.held & b) != 0 ? 1.0 : 0.0; };
  const Vec2 f{held(button_right) - held(button_left), held(button_up) - held(button_down)};
  return {world.find(names[static_cast<std::size_t>(i)]), BodyInputKind::force, f * thrust};
}

struct KingOfTheHill {
  std::array<int, 2> score{};
  int player = 0;  // the local player (seat)

  void setup(WorldDef& level) {
    level.settings = {.dt = 1.0 / 120.0, .integrator = Integrator::semi_implicit_euler};
    level.settings.contacts = ContactSettings{.restitution = 0.6, .friction = 0.0};
    for (int i = 0; i < 2; ++i) {
      BodyDef b;
      b.name = names[static_cast<std::size_t>(i)];
      b.body = Body{.mass = 1.0, .position = {i == 0 ? -3.0 : 3.0, 0.0}, .velocity = {}};
      b.collider = Collider{.radius = 0.4};
      b.drag = LinearDrag{.coefficient = 1.5};  // N·s/m: a disc left alone slows down
      b.appearance = Appearance{
          .radius = 0.4, .color = i == 0 ? Rgba8{230, 70, 70, 255} : Rgba8{70, 130, 240, 255}};
      level.add_body(b);
    }
    for (const Vec2 n : {Vec2{1, 0}, Vec2{-1, 0}, Vec2{0, 1}, Vec2{0, -1}}) {
      level.planes.push_back({.normal = n, .offset = -4.5, .restitution = 0.6});
    }
  }
  // The rules, as single-player: a point a tick for the disc alone in the ring.
  void rules(World& world, const TickInput&) {
    std::array<bool, 2> in{};
    for (int i = 0; i < 2; ++i) {
      const Vec2 p = world.body(world.find(names[static_cast<std::size_t>(i)])).position;
      in[static_cast<std::size_t>(i)] = p.x * p.x + p.y * p.y < ring * ring;
    }
    if (in[0] != in[1]) ++score[in[0] ? 0 : 1];
  }
  // Single-player: the local player's arrows push red (app::run calls prepare, never merge).
  void prepare(TickInput& input, const World& world) { input.bodies = {push(0, input, world)}; }
  // Networked: the two changes.
  void seat(int p) { player = p; }
  [[nodiscard]] TickInput merge(std::span<const TickInput> players, const World& world) const {
    TickInput out;
    for (int i = 0; i < static_cast<int>(players.size()) && i < 2; ++i) {
      out.bodies.push_back(push(i, players[static_cast<std::size_t>(i)], world));
    }
    return out;
  }
  // A bot (--bot, and headless single-player runs): towards the ring, then wrestling, by tick.
  void autopilot(std::int64_t frame, const World&, InputSampler& sampler) {
    sampler.release(button_left | button_right | button_up | button_down);
    if (player == 1 && frame < 60) return;  // blue starts late: red gets the ring first
    const bool wrestle = frame > 60 && (frame / 40) % 2 == 0;
    sampler.press(player == 0 ? (wrestle ? button_up : button_right)
                              : (wrestle ? button_down : button_left));
  }
  void draw(app::Overlay& overlay) const {
    overlay.circle({0.0, 0.0}, ring, 0.05, Rgba8{255, 255, 255, 160});
    overlay.text("red " + std::to_string(score[0]) + "  blue " + std::to_string(score[1]) +
                 "   (you: " + names[static_cast<std::size_t>(player)] + ")");
  }
  [[nodiscard]] std::string summary() const {
    return "red=" + std::to_string(score[0]) + " blue=" + std::to_string(score[1]);
  }
};

}  // namespace

int main(int argc, char** argv) {
  return net::run(KingOfTheHill{},
                  {.name = "11_networked_game",
                   .description = "king of the hill, alone or over the network",
                   .width = 640,
                   .height = 640,
                   .view_center = Vec2{0.0, 0.0},
                   .view_width = 10.0,
                   .controls = "arrows: push your disc"},
                  argc, argv);
}
