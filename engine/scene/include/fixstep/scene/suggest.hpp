// "Did you mean ...?" for misspelt names (scene keys, command-line options).
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace fixstep {

/// Levenshtein distance: the fewest single-character insertions, deletions and substitutions
/// turning a into b (Levenshtein, Soviet Physics Doklady 10(8), 1966; the two-row dynamic
/// programme of Wagner & Fischer, JACM 21(1), 1974). O(|a|·|b|) time, O(|b|) memory.
[[nodiscard]] std::size_t edit_distance(std::string_view a, std::string_view b);

/// The candidate closest to `word` if it is within `max_distance` edits (ties: the first), else
/// nullopt; e.g. closest("stifness", {"stiffness", "damping"}) == "stiffness".
[[nodiscard]] std::optional<std::string> closest(std::string_view word,
                                                 std::span<const std::string> candidates,
                                                 std::size_t max_distance = 2);

}  // namespace fixstep
