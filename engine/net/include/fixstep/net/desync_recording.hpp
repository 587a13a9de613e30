// A peer's recording kept after a desync, so that the peers' runs can be replayed and compared
// offline (docs/NETWORK.md, "Desync detection").
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "fixstep/net/match_peer.hpp"

namespace fixstep::net {

/// Writes `peer`'s recording (MatchPeer::recording(): its confirmed ticks, each with its state
/// hash) into `dir` as STEM-desync-pSLOT-tTICK.rec, TICK being the desync's tick
/// (MatchPeer::desync()), or the recording's length when there is no report; when that name is
/// taken (by any kind of file, a link included) -2, -3, … up to -99 is added before ".rec", so
/// no file is ever replaced. The file is written atomically (io's write_recording). Returns the
/// path written. Throws std::runtime_error naming the directory when all 99 names are taken,
/// or io's error (naming the file and the system's reason) when it cannot be written.
[[nodiscard]] std::filesystem::path write_desync_recording(const MatchPeer& peer,
                                                           const std::filesystem::path& dir,
                                                           const std::string& stem);

/// Writes `peer`'s state of a located desync's first differing tick (MatchPeer::desync_state)
/// into `dir` as STEM-desync-pSLOT-tTICK.state (named as write_desync_recording names, never
/// over a file or a link), a text of a line per body: index, name, x, y, vx, vy, θ, ω, sleep
/// ticks and island, each exact (shortest round-trip decimals), and random()'s state. Compare
/// two peers' files line by line. Returns nullopt when there is no such state (no desync
/// located, or its state could not be re-simulated). Throws as write_desync_recording.
[[nodiscard]] std::optional<std::filesystem::path> write_desync_state(
    const MatchPeer& peer, const std::filesystem::path& dir, const std::string& stem);

/// Moves the recording file `written` (a peer's, streamed: MatchSettings::record_file, finished
/// by MatchPeer::finish_recording) into `dir` under the name write_desync_recording would pick
/// for a peer of slot `slot` desynced at `tick` (never over a file or a link) and returns that
/// path. Throws std::runtime_error as write_desync_recording, or naming both files when the
/// rename fails.
[[nodiscard]] std::filesystem::path move_desync_recording(const std::filesystem::path& written,
                                                          const std::filesystem::path& dir,
                                                          const std::string& stem,
                                                          std::uint8_t slot, std::uint64_t tick);

}  // namespace fixstep::net
