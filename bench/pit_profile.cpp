// The ball pit's rollback under a profiler: settle it, save, then restore and re-simulate, with
// no timing of its own (run it under valgrind --tool=callgrind and read the instruction counts
// of World::restore and World::step; wall clocks on a shared machine are not to be trusted).
//
//   pit_profile [--settle N] [--rollbacks R] [--resim K] [--threads T] [scene.toml]
//
// Defaults: assets/scenes/ball_pit.toml, settle 400 ticks (bench_net's rollback level), 10
// rollbacks of 9 ticks each (8 re-simulated ticks plus the frame's own), threads 0 (automatic).
// Prints the final state hash, so two builds can be checked to step the same bits.
#include <fmt/format.h>

#include <cstdlib>
#include <string>
#include <string_view>

#include "fixstep/core/input.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/scene/scene.hpp"

using namespace fixstep;

int main(int argc, char** argv) {
  std::string scene = FIXSTEP_SOURCE_DIR "/assets/scenes/ball_pit.toml";
  long settle = 400, rollbacks = 10, resim = 9, threads = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string_view a = argv[i];
    long* value = a == "--settle"      ? &settle
                  : a == "--rollbacks" ? &rollbacks
                  : a == "--resim"     ? &resim
                  : a == "--threads"   ? &threads
                                       : nullptr;
    if (value && i + 1 < argc) {
      *value = std::strtol(argv[++i], nullptr, 10);
    } else if (!a.starts_with("--")) {
      scene = argv[i];
    } else {
      fmt::print(stderr,
                 "usage: pit_profile [--settle N] [--rollbacks R] [--resim K] "
                 "[--threads T] [scene.toml]\n");
      return 2;
    }
  }
  WorldDef def = load_scene(scene).def;
  def.settings.threads = static_cast<int>(threads);
  World world(def);
  for (long t = 0; t < settle; ++t) world.step(TickInput{world.tick()});
  const ContactStats& c = world.contact_stats();
  fmt::print(
      "tick {}: {} candidate pairs, {} impacts, {} touching, {} velocity and {} position "
      "sweeps; a snapshot holds {} bytes\n",
      world.tick(), c.candidate_pairs, c.impacts, c.touching, c.velocity_sweeps, c.position_sweeps,
      world.snapshot_bytes());
  WorldSnapshot snap;
  world.save(snap);
  for (long k = 0; k < rollbacks; ++k) {
    world.restore(snap);
    for (long t = 0; t < resim; ++t) world.step(TickInput{world.tick()});
  }
  fmt::print("tick {} hash {:016x}\n", world.tick(), world.state_hash());
  return 0;
}
