// The scene-loader fuzz check of one input, shared by the libFuzzer target (fuzz_scene.cpp,
// clang only) and the GoogleTest replay of the corpus and regressions (fuzz_regressions.cpp).
// See docs/ROBUSTNESS.md, "Fuzzing".
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace fixstep::fuzz {

enum class Verdict {
  accepted,           ///< loaded, built and stepped with every state finite
  rejected,           ///< parse_scene threw SceneError, or World(scene.def) refused it with the
                      ///< stability guard (UnstableDefinition, located): a clean rejection
  rejected_by_world,  ///< World(scene.def) threw std::invalid_argument (documented, but the
                      ///< loader is meant to catch these first; fatal with FIXSTEP_FUZZ_STRICT=1)
  overflowed,         ///< a state became non-finite in a scene outside the checked range
                      ///< (see bounded_scene): tolerated (fatal with FIXSTEP_FUZZ_STRICT=1)
  finding,            ///< another exception type escaped, or a state of a bounded scene
                      ///< became non-finite
};

struct Outcome {
  Verdict verdict = Verdict::accepted;
  std::string detail;  ///< the exception's message or the non-finite body; empty if accepted
};

/// Ticks stepped for an accepted scene.
inline constexpr int max_ticks = 60;
/// Bound on the work of one input, in body-substeps ((bodies + links) x substeps x ticks): a
/// scene may ask for up to 10^6 substeps per tick, so a heavy scene steps fewer ticks (at least
/// one). Implicit Euler on a world with links solves a sparse system per step (Newton with a
/// sparse LU per iteration), counted as (bodies + links) x bodies per substep. With [contacts]
/// on, each disc counts disc_weight more: a pile of 1 200 touching discs (a mutated
/// galton_board.toml) took 200 ms a tick under ASan, 12 s for 60 ticks, past the timeout.
inline constexpr std::uint64_t max_body_substeps = 4'000'000;
/// Extra body-substeps a disc counts for in a world with [contacts] (broadphase, impacts at
/// their time, the resting-contact solver): about its cost relative to a plain body there.
inline constexpr std::uint64_t disc_weight = 400;
/// A scene whose world or first tick would be bigger than the check can afford within
/// libFuzzer's per-input timeout is only loaded (parse_scene), not built or stepped: more than
/// this many bodies + links (generators make up to 10^6 bodies from a few bytes; building and
/// stepping them under ASan takes over 10 s and nearly 2 GB), or one tick beyond
/// max_body_substeps.
inline constexpr std::uint64_t max_built_size = 200'000;

/// Magnitudes inside which a non-finite state is a bug rather than arithmetic overflow: with
/// every number of a scene at most 1e9 in magnitude, every mass at least 1e-9 kg, dt <= 1 s and
/// the stability guard on, 60 s of forcing moves a body less than 1e9 + 1e9 * 60 + 1e18 * 60^2
/// ~ 4e21 m, far inside float range. The scene format itself admits any finite number
/// (position = [1e308, 0] with velocity = [1e308, 0] overflows on the first tick), and
/// allow_unstable = true asks for blow-ups.
inline constexpr double bounded_max = 1e9;
inline constexpr double bounded_min_mass = 1e-9;

/// parse_scene(text, "fuzz.toml"), World(scene.def), then up to max_ticks ticks checking every
/// body's position and velocity after each tick. Crashes and sanitizer reports are left to
/// the caller's process.
[[nodiscard]] Outcome check_scene_text(std::string_view text);

}  // namespace fixstep::fuzz
