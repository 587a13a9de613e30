// The golden determinism matrix on core and scene alone: every shipped scene x integrator x
// precision the stability guard accepts, stepped a fixed number of ticks and hashed
// (World::state_hash). Shared by tests/core/test_determinism.cpp (GoogleTest, native) and the
// cross-architecture programs in this directory (aarch64 under qemu, wasm32 under node), so
// every platform checks the same cases against the same tests/golden/state_hashes.txt.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "fixstep/core/input.hpp"
#include "fixstep/core/integrators.hpp"
#include "fixstep/scene/scene.hpp"

namespace fixstep::determinism {

/// Ticks the golden hashes are taken after (fewer for the costly scenes: ticks_for).
inline constexpr std::uint64_t golden_ticks = 1000;

/// assets/scenes and tests/golden/state_hashes.txt of the source tree this was built from.
[[nodiscard]] std::filesystem::path scenes_dir();
[[nodiscard]] std::filesystem::path golden_file();

struct Case {
  std::string scene;  ///< file name in scenes_dir()
  Integrator integrator;
  Precision precision;
  /// "SCENE INTEGRATOR PRECISION", the golden file's key.
  [[nodiscard]] std::string key() const;
};

/// The case's scene loaded from scenes_dir() with its integrator and precision set. Throws
/// SceneError as load_scene does.
[[nodiscard]] Scene scene_for(const Case& c);

/// `ticks` for most scenes; a quarter for ball_pit.toml and half for galton_board.toml, whose
/// ticks cost far more than the others' (see the definition).
[[nodiscard]] std::uint64_t ticks_for(const std::string& scene, std::uint64_t ticks);

/// Every shipped scene with every integrator and precision the stability guard accepts, sorted
/// by file name (implicit Euler on scenes with more than 40 links left out: see the definition).
[[nodiscard]] std::vector<Case> all_cases();

/// State hash after ticks_for(c.scene, ticks) ticks without input, stepping directly.
[[nodiscard]] std::uint64_t hash_direct(const Case& c, std::uint64_t ticks);

/// golden_file() as key -> 16 hex digits (comment lines skipped; empty if it cannot be read).
[[nodiscard]] std::map<std::string, std::string> read_golden();

/// An input that changes every few ticks (the sync tests' script): a push for 10 of every 50
/// ticks (0.5, -0.25 m/s²) and a drag of body 0 towards (0.3, 0.2) m for 15 of every 70.
[[nodiscard]] TickInput scripted_input(std::uint64_t t);

}  // namespace fixstep::determinism
