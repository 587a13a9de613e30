// The lines of a recording file, shared by format_recording (recording_format.cpp) and the
// streaming RecordingWriter (recording_writer.cpp), so both write the same bytes. Internal to
// the engine: not installed.
#pragma once

#include <cstdint>
#include <string>

#include "fixstep/recording.hpp"

namespace fixstep::recording_text {

/// The header: "fixstep-recording VERSION" through "hash_every K", each line ending in '\n'.
/// Throws std::invalid_argument for a scene path holding a control character.
[[nodiscard]] std::string header(const Recording& rec);
/// Appends "tick N push=... drag=... [per-body inputs]\n".
void append_tick(std::string& out, const TickInput& input);
/// Appends "hash N HASH\n".
void append_hash(std::string& out, std::uint64_t tick, std::uint64_t hash);
/// Appends "end TICKS HASH\n".
void append_end(std::string& out, std::uint64_t ticks, std::uint64_t hash);

}  // namespace fixstep::recording_text
