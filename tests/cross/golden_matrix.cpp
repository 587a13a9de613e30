// golden_matrix: every case of the golden determinism matrix (determinism_cases.hpp) stepped
// here and compared with tests/golden/state_hashes.txt: the same check as
// Determinism.GoldenStateHashesOfEveryShippedScene, on core and scene alone, so the aarch64
// (qemu) and wasm32 (node) builds run it. Prints each mismatch ("KEY: got H, golden G") and a
// summary; exit 0 when every case matches and the file has no other keys, 1 otherwise.
//   golden_matrix [FILTER]   only the cases whose key contains FILTER (then extra keys are fine)
//   golden_matrix --shard I/N   only the cases whose place in the matrix is I modulo N (0 <= I <
//   N):
//                               N programs run side by side, each on a core (an emulator's run is
//                               single-threaded); shard 0 also checks the file has no other keys
#include <cstdio>
#include <exception>
#include <string>

#include "determinism_cases.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/io/summary.hpp"

int main(int argc, char** argv) {
  using namespace fixstep;
  using namespace fixstep::determinism;
  std::string filter = argc > 1 ? argv[1] : "";
  int shard = 0, shards = 1;
  if (filter == "--shard") {
    if (argc != 3 || std::sscanf(argv[2], "%d/%d", &shard, &shards) != 2 || shards < 1 ||
        shard < 0 || shard >= shards) {
      std::printf("golden_matrix: --shard takes I/N with 0 <= I < N (got %s)\n",
                  argc > 2 ? argv[2] : "nothing");
      return 2;
    }
    filter.clear();
  }
  try {
    const auto golden = read_golden();
    if (golden.empty()) {
      std::printf("golden_matrix: no hashes in %s\n", golden_file().string().c_str());
      return 1;
    }
    int checked = 0, failed = 0, place = -1, matched = 0;
    for (const Case& c : all_cases()) {
      const std::string key = c.key();
      if (key.find(filter) == std::string::npos) continue;
      ++matched;
      if (++place % shards != shard) continue;
      ++checked;
      const auto it = golden.find(key);
      const std::string got = hex_hash(hash_direct(c, golden_ticks));
      if (it == golden.end() || it->second != got) {
        ++failed;
        std::printf("%s: got %s, golden %s\n", key.c_str(), got.c_str(),
                    it == golden.end() ? "(none)" : it->second.c_str());
      }
    }
    const bool extra = filter.empty() && shard == 0 && matched != static_cast<int>(golden.size());
    if (extra) std::printf("the golden file has %zu keys for %d cases\n", golden.size(), matched);
    std::printf("golden_matrix: %d of %d cases match\n", checked - failed, checked);
    return failed == 0 && !extra && checked > 0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::printf("golden_matrix: %s\n", e.what());
    return 1;
  }
}
