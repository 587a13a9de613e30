// sync_matrix: the sync test (fixstep/core/sync_test.hpp: roll back K = 7 ticks at every tick,
// re-simulate, compare hash and dissipated energy bit for bit) over every case of the golden
// matrix (determinism_cases.hpp) with the scripted input, on core and scene alone, so the
// aarch64 (qemu) and wasm32 (node) builds run it. Also checks that the rolled-back run ends in
// the state of a plain run. Exit 0 when all pass, 1 otherwise (each failure printed).
//   sync_matrix [TICKS] [FILTER]   TICKS per case (default 60); only keys containing FILTER
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "determinism_cases.hpp"
#include "fixstep/core/sync_test.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/io/summary.hpp"

namespace {

using namespace fixstep;
using namespace fixstep::determinism;

/// Empty when the case passes, else what went wrong.
std::string check(const Case& c, std::uint64_t ticks) {
  const Scene scene = scene_for(c);
  ticks = ticks_for(c.scene, ticks);
  World plain = World(scene.def);
  World tested = World(scene.def);
  SyncTest sync(tested, 7);
  for (std::uint64_t t = 0; t < ticks; ++t) {
    plain.step(scripted_input(t));
    if (!sync.step(scripted_input(t))) {
      const auto& m = *sync.mismatch();
      return "re-simulated tick " + std::to_string(m.tick) + " gave " + hex_hash(m.actual) +
             ", first run " + hex_hash(m.expected) +
             (m.dissipated_differs ? " (dissipated energy differs)" : "");
    }
  }
  if (tested.state_hash() != plain.state_hash()) return "the rolled-back run ends elsewhere";
  return "";
}

}  // namespace

int main(int argc, char** argv) {
  const std::uint64_t ticks = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 60;
  const std::string filter = argc > 2 ? argv[2] : "";
  try {
    int checked = 0, failed = 0;
    for (const Case& c : all_cases()) {
      if (c.key().find(filter) == std::string::npos) continue;
      ++checked;
      if (const std::string why = check(c, ticks); !why.empty()) {
        ++failed;
        std::printf("%s: %s\n", c.key().c_str(), why.c_str());
      }
    }
    std::printf("sync_matrix: %d of %d cases roll back bit-exactly over %llu ticks\n",
                checked - failed, checked, static_cast<unsigned long long>(ticks));
    return failed == 0 && checked > 0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::printf("sync_matrix: %s\n", e.what());
    return 1;
  }
}
