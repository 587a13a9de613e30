// Internal: the game type app::run is given, behind one interface, so that run()'s modes are
// compiled once in the library rather than in every game.
#pragma once

#include <concepts>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <utility>

#include "fixstep/app/overlay.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/render/user_events.hpp"

namespace fixstep::app {
struct Settings;
}

namespace fixstep::app::detail {

/// A game of any type: its hooks, the missing optional ones doing nothing.
class AnyGame {
 public:
  virtual ~AnyGame() = default;
  /// A copy in the current state (run() keeps the untouched original to start afresh).
  [[nodiscard]] virtual std::unique_ptr<AnyGame> clone() const = 0;
  /// Becomes a copy of `other`, a game of the same type (a rollback).
  virtual void assign(const AnyGame& other) = 0;
  virtual void setup(WorldDef& level) = 0;
  virtual void rules(World& world, const TickInput& input) = 0;
  virtual void input(const UserEvents& ev, const World& world, InputSampler& sampler) = 0;
  virtual void autopilot(std::int64_t frame, const World& world, InputSampler& sampler) = 0;
  virtual void prepare(TickInput& input, const World& world) = 0;
  virtual void draw(Overlay& overlay) const = 0;
  /// The game's pre-solve hook (World::set_pre_solve) installed on `world` with this game as its
  /// context, when the game has a pre_solve(); nothing otherwise.
  virtual void attach(World& world) = 0;
  [[nodiscard]] virtual std::string summary() const = 0;
  /// Networked play: the player this program's input() and autopilot() play (0 = the host).
  virtual void seat(int player) = 0;
  /// Networked play: the tick's input from every player's (index = player), into `out`;
  /// false when the game has no merge() (the network's default merge applies).
  [[nodiscard]] virtual bool merge(std::span<const TickInput> players, const World& world,
                                   TickInput& out) const = 0;

 protected:
  AnyGame() = default;
  AnyGame(const AnyGame&) = default;
  AnyGame& operator=(const AnyGame&) = default;
};

template <class G>
class GameModel final : public AnyGame {
 public:
  explicit GameModel(G game) : game_(std::move(game)) {}
  [[nodiscard]] std::unique_ptr<AnyGame> clone() const override {
    return std::make_unique<GameModel>(*this);
  }
  void assign(const AnyGame& other) override { game_ = static_cast<const GameModel&>(other).game_; }
  void setup(WorldDef& level) override { game_.setup(level); }
  void rules(World& world, const TickInput& input) override { game_.rules(world, input); }
  void input(const UserEvents& ev, const World& world, InputSampler& sampler) override {
    if constexpr (requires { game_.input(ev, world, sampler); }) game_.input(ev, world, sampler);
  }
  void autopilot(std::int64_t frame, const World& world, InputSampler& sampler) override {
    if constexpr (requires { game_.autopilot(frame, world, sampler); }) {
      game_.autopilot(frame, world, sampler);
    }
  }
  void prepare(TickInput& input, const World& world) override {
    if constexpr (requires { game_.prepare(input, world); }) game_.prepare(input, world);
  }
  void draw(Overlay& overlay) const override {
    if constexpr (requires { game_.draw(overlay); }) game_.draw(overlay);
  }
  void attach(World& world) override {
    if constexpr (requires(const PreSolveContact& c) {
                    { game_.pre_solve(c) } -> std::convertible_to<bool>;
                  }) {
      world.set_pre_solve(
          [](const PreSolveContact& c, void* self) {
            return static_cast<bool>(static_cast<const GameModel*>(self)->game_.pre_solve(c));
          },
          this);
    }
  }
  [[nodiscard]] std::string summary() const override {
    if constexpr (requires { game_.summary(); }) {
      return std::string(game_.summary());
    } else {
      return {};
    }
  }
  void seat(int player) override {
    if constexpr (requires { game_.seat(player); }) game_.seat(player);
  }
  [[nodiscard]] bool merge(std::span<const TickInput> players, const World& world,
                           TickInput& out) const override {
    if constexpr (requires { out = game_.merge(players, world); }) {
      out = game_.merge(players, world);
      return true;
    } else {
      return false;
    }
  }

 private:
  G game_;
};

/// app::run's body: parses the command line and runs the mode it names with copies of `game`,
/// its results on standard output checked (with_results_on_standard_output: a closed or full
/// standard output is an error, not a silent loss).
[[nodiscard]] int run_game(const AnyGame& game, const Settings& settings, int argc, char** argv);
/// run_game without the check of standard output, for a caller that checks it around more
/// (net::run).
[[nodiscard]] int run_game_unchecked(const AnyGame& game, const Settings& settings, int argc,
                                     char** argv);

}  // namespace fixstep::app::detail
