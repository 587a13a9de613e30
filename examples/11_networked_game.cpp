// A single-player game made networked. King of the hill: each player pushes its own disc with
// the arrow keys, and scores a point a tick while its disc alone is in the ring. Written for
// fixstep::app::run, it becomes a game of two to eight players over the network with three
// changes (and Settings::max_players = 8):
//   1. main() calls fixstep::net::run instead of app::run (link fixstep::net_app): the program
//      gets --host PORT and --join HOST:PORT (and --session lockstep|rollback, --record, ...);
//   2. seat(player): which player this program plays (its input and its bot);
//   3. merge(players, world): the tick's one input from every player's, run on every peer
//      inside the tick (deterministic, like the rules): player i's arrows push disc i.
// The rules and their state are unchanged: every peer runs them after each tick, and a match's
// recording replays with them (--replay) like a single-player one.
//
//   11_networked_game --host 7777                     player 0 (in a window); prints the token T
//   11_networked_game --join 127.0.0.1:7777 --token T           player 1
//   11_networked_game --host 7777 --players 4         a match of four (three join)
//   11_networked_game --spectate 127.0.0.1:7777 --token T       watch it
//   11_networked_game --host 0 --bot --ticks 240 --record a.rec     scripted, headless
//   11_networked_game --replay a.rec                  verify the match's recording
#include <array>
#include <fixstep/core/components.hpp>
#include <fixstep/core/input.hpp>
#include <fixstep/core/world_def.hpp>
#include <fixstep/core/world_settings.hpp>
#include <fixstep/net_app/run.hpp>
#include <span>
#include <string>

namespace {

using namespace fixstep;

constexpr double ring = 2.0;    // m, the ring's radius
constexpr double thrust = 6.0;  // N, the arrows' force on a 1 kg disc
constexpr int seats = 8;        // discs in the level: one per possible player
constexpr std::array<const char*, seats> names{"red",    "blue", "green", "gold",
                                               "violet", "cyan", "white", "orange"};
constexpr std::array<Rgba8, seats> colours{Rgba8{230, 70, 70, 255},   Rgba8{70, 130, 240, 255},
                                           Rgba8{80, 200, 100, 255},  Rgba8{240, 200, 60, 255},
                                           Rgba8{170, 90, 230, 255},  Rgba8{70, 220, 220, 255},
                                           Rgba8{235, 235, 235, 255}, Rgba8{250, 140, 40, 255}};
// Where each disc starts, m: around the ring, players 0 and 1 face each other.
constexpr std::array<Vec2, seats> starts{Vec2{-3.0, 0.0}, Vec2{3.0, 0.0},  Vec2{0.0, 3.0},
                                         Vec2{0.0, -3.0}, Vec2{-2.5, 2.5}, Vec2{2.5, -2.5},
                                         Vec2{2.5, 2.5},  Vec2{-2.5, -2.5}};

/// Player `i`'s held arrows as a force on its disc, N.
BodyInput push(int i, const TickInput& in, const World& world) {
  const auto held = [&](std::uint32_t b) { return (in.held & b) != 0 ? 1.0 : 0.0; };
  const Vec2 f{held(button_right) - held(button_left), held(button_up) - held(button_down)};
  return {world.find(names[static_cast<std::size_t>(i)]), BodyInputKind::force, f * thrust};
}

struct KingOfTheHill {
  std::array<int, seats> score{};
  int player = 0;  // the local player (seat)

  void setup(WorldDef& level) {
    level.settings = {.dt = 1.0 / 120.0, .integrator = Integrator::semi_implicit_euler};
    level.settings.contacts = ContactSettings{.restitution = 0.6, .friction = 0.0};
    for (std::size_t i = 0; i < seats; ++i) {
      BodyDef b;
      b.name = names[i];
      b.body = Body{.mass = 1.0, .position = starts[i], .velocity = {}};
      b.collider = Collider{.radius = 0.4};
      b.drag = LinearDrag{.coefficient = 1.5};  // N·s/m: a disc left alone slows down
      b.appearance = Appearance{.radius = 0.4, .color = colours[i]};
      level.add_body(b);
    }
    for (const Vec2 n : {Vec2{1, 0}, Vec2{-1, 0}, Vec2{0, 1}, Vec2{0, -1}}) {
      level.planes.push_back({.normal = n, .offset = -4.5, .restitution = 0.6});
    }
  }
  // The rules, as single-player: a point a tick for the disc alone in the ring.
  void rules(World& world, const TickInput&) {
    int inside = 0, last = 0;
    for (std::size_t i = 0; i < seats; ++i) {
      const Vec2 p = world.body(world.find(names[i])).position;
      if (p.x * p.x + p.y * p.y < ring * ring) ++inside, last = static_cast<int>(i);
    }
    if (inside == 1) ++score[static_cast<std::size_t>(last)];
  }
  // Single-player: the local player's arrows push red (app::run calls prepare, never merge).
  void prepare(TickInput& input, const World& world) { input.bodies = {push(0, input, world)}; }
  // Networked: the two changes.
  void seat(int p) { player = p; }
  [[nodiscard]] TickInput merge(std::span<const TickInput> players, const World& world) const {
    TickInput out;
    for (int i = 0; i < static_cast<int>(players.size()) && i < seats; ++i) {
      out.bodies.push_back(push(i, players[static_cast<std::size_t>(i)], world));
    }
    return out;
  }
  // A bot (--bot, and headless single-player runs): towards the ring, then wrestling, by tick;
  // player p sets off 30 p ticks after red, so red gets the ring first.
  void autopilot(std::int64_t frame, const World&, InputSampler& sampler) {
    sampler.release(button_left | button_right | button_up | button_down);
    const std::int64_t off = std::int64_t{30} * player;  // this player's start, ticks
    if (frame < off) return;
    const Vec2 from = starts[static_cast<std::size_t>(player)];
    const bool wrestle = frame > off + 60 && (frame / 40) % 2 == 0;
    if (from.x < 0.0) sampler.press(button_right);
    if (from.x > 0.0) sampler.press(button_left);
    if (from.y < 0.0) sampler.press(button_up);
    if (from.y > 0.0) sampler.press(button_down);
    if (wrestle) sampler.press((player % 2 == 0) ? button_up : button_down);
  }
  void draw(app::Overlay& overlay) const {
    overlay.circle({0.0, 0.0}, ring, 0.05, Rgba8{255, 255, 255, 160});
    overlay.text(summary() + "   (you: " + names[static_cast<std::size_t>(player)] + ")");
  }
  // The scores of the discs that scored (red's and blue's always).
  [[nodiscard]] std::string summary() const {
    std::string s;
    for (std::size_t i = 0; i < seats; ++i) {
      if (i >= 2 && score[i] == 0) continue;
      s += (s.empty() ? "" : " ") + std::string(names[i]) + "=" + std::to_string(score[i]);
    }
    return s;
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
                   .controls = "arrows: push your disc",
                   .max_players = seats},
                  argc, argv);
}
