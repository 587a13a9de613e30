// A world's state as a text file, body by body, every value exact: what a networked peer
// writes of its state at a desync's first differing tick (net::write_desync_state), and what
// `fixstep diff` and a game's --diff compare when two recordings' states differ but replay
// alike (the divergence happened on a peer, not in its inputs).
//
//   # fixstep state: slot 1 after tick 96 (...)
//   state tick 96 precision f64 rolling 0 sleep 0
//   random 0x0123456789abcdef            (or: random not drawn)
//   body 0 "left" x y vx vy theta omega sleep_ticks island
//
// Values are shortest round-trip decimals (read back to the same bits); names in double quotes
// (the text up to the line's last quote).
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "fixstep/core/state_difference.hpp"

namespace fixstep {

/// A state file read back: the fields and each body's name (index = body).
struct StateFile {
  StateFields fields;
  std::vector<std::string> names;
};

/// Most bytes of a state file read (a world of max_state_bodies-sized scale is larger than any
/// desync's peer writes: 64 MiB, about 500 000 bodies).
inline constexpr std::size_t max_state_file_bytes = std::size_t{64} << 20;

/// The text of `fields` with `names` (one per body, or fewer: the rest unnamed) under a first
/// comment line `title`.
[[nodiscard]] std::string format_state_file(const StateFields& fields,
                                            const std::vector<std::string>& names,
                                            const std::string& title);

/// Reads a state file. Throws FileReadError (missing, not a regular file, over
/// max_state_file_bytes, unreadable) or std::runtime_error "FILE:LINE: WHAT" for a line that is
/// not one of the format's (a missing or repeated state line, a body out of order, a number
/// that does not read whole).
[[nodiscard]] StateFile read_state_file(const std::filesystem::path& file);

/// The state file beside a recording: `recording` with its extension replaced by ".state"
/// (NAME-desync-p1-t96.rec -> NAME-desync-p1-t96.state).
[[nodiscard]] std::filesystem::path state_file_beside(const std::filesystem::path& recording);

/// What compare_states_beside found: a line to print, and whether the files could be read.
struct StatesBeside {
  std::string text;
  bool read = true;  ///< false: `text` says which file and line could not be read
};

/// When both recordings have a state file beside them (state_file_beside), both read, and of the
/// same tick: a line naming their first difference (first_difference, names from a's file), or
/// saying they are equal. nullopt when either file is missing. A file that cannot be read gives
/// a line saying so (naming the file, the line and what is wrong; `read` false): the recordings'
/// own comparison stands either way.
[[nodiscard]] std::optional<StatesBeside> compare_states_beside(
    const std::filesystem::path& recording_a, const std::filesystem::path& recording_b);

}  // namespace fixstep
