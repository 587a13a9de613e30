// Test helper: a lockstep match of several peers on loopback, through a link conditioner,
// polled from one thread until every peer is done or a deadline passes (never hangs).
#pragma once

#include <chrono>
#include <fixstep/link_conditioner.hpp>
#include <fixstep/lockstep.hpp>
#include <fixstep/scene.hpp>
#include <functional>
#include <memory>
#include <optional>
#include <thread>
#include <vector>

namespace fixstep::net_test {

/// The billiards scene (16 discs, four cushions) with its text, as a recording carries it.
inline const Scene& billiards() {
  static const Scene scene =
      load_scene(std::string(FIXSTEP_SOURCE_DIR) + "/assets/scenes/billiards.toml");
  return scene;
}

/// Player `slot`'s scripted input of `tick`: an impulse on its own ball now and then, the
/// pointer moving in steps, a button held in spells (so presses and releases too).
inline TickInput scripted_input(const World& world, std::uint8_t slot, std::uint64_t tick) {
  TickInput in;
  const auto bodies = world.bodies();
  if (tick % 25 == slot % 25) {
    const double s = static_cast<double>(slot) + 1.0;
    in.bodies.push_back({bodies[slot % bodies.size()],
                         BodyInputKind::impulse,
                         {0.002 * s, -0.001 * s * static_cast<double>(tick % 3)}});
  }
  const bool held = ((tick / 40) + slot) % 3 == 0;
  in.held = held ? std::uint32_t{button_left} : 0u;
  in.pointer = {0.1 * slot, 0.01 * static_cast<double>(tick / 10)};
  return in;
}

/// The peers of one match: the host first, then the joiners (players, then spectators).
struct Match {
  std::vector<std::unique_ptr<net::LockstepPeer>> peers;
  std::unique_ptr<net::LinkConditioner> link;
  std::vector<std::uint8_t> held_edges;  // per peer: the previous tick's held bits

  /// Polls everything, gives inputs where wanted (scripted_input, with pressed/released from
  /// the held bits), steps, until every peer is finished, one fails or desyncs, or
  /// `deadline_ms` passes. `each_tick(peer index)` runs after each advance (tests' hooks).
  /// Returns whether every peer finished.
  bool run(double deadline_ms, const std::function<void(std::size_t)>& each_tick = {}) {
    const auto start = std::chrono::steady_clock::now();
    std::vector<std::uint32_t> prev_held(peers.size(), 0);
    for (;;) {
      if (link) link->pump();
      bool all_done = true;
      for (std::size_t i = 0; i < peers.size(); ++i) {
        net::LockstepPeer& p = *peers[i];
        p.poll(0);
        while (p.wants_input()) {
          TickInput in = scripted_input(p.world(), p.slot(), p.next_input_tick());
          in.pressed = in.held & ~prev_held[i];
          in.released = prev_held[i] & ~in.held;
          prev_held[i] = in.held;
          p.add_input(in);
        }
        (void)p.advance();
        if (each_tick) each_tick(i);
        const net::MatchState s = p.state();
        if (s == net::MatchState::failed || s == net::MatchState::desynced) return false;
        all_done = all_done && s == net::MatchState::finished;
      }
      if (all_done) {
        // A few more rounds so the last acknowledgements and hashes arrive.
        for (int k = 0; k < 20; ++k) {
          if (link) link->pump();
          for (auto& p : peers) p->poll(0);
          std::this_thread::sleep_for(std::chrono::milliseconds(1));
        }
        return true;
      }
      const double elapsed =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
              .count();
      if (elapsed > deadline_ms) return false;
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
  }
};

}  // namespace fixstep::net_test
