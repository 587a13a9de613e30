// Recordings as bytes and files: the line-oriented text of a Recording (recording.hpp) made and
// parsed in a buffer the caller owns, the errors of a recording that cannot be used, and the
// file helpers around them (read bounded, written atomically). Format: docs/CLI.md, "Recording
// and replay".
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

#include "fixstep/core/recording.hpp"
#include "fixstep/core/world_def.hpp"

namespace fixstep {

/// The first word of every recording (the first line is "fixstep-recording VERSION").
inline constexpr std::string_view recording_magic = "fixstep-recording";
/// Largest recording file read, bytes.
inline constexpr std::size_t max_recording_bytes = 256u << 20;
/// A recording that cannot be used. what() reads "FILE:LINE: FIELD: MESSAGE" (line and field
/// left out when they do not apply).
class RecordingError : public std::runtime_error {
 public:
  enum class Kind {
    unreadable,           ///< the file cannot be opened or read (missing, a directory)
    foreign,              ///< not a recording: the first line is not "fixstep-recording N"
    unsupported_version,  ///< a recording of a version newer than recording_version
    truncated,            ///< the file ends before its `end` line (a session cut short)
    corrupt,              ///< a malformed line or field, a value out of range, an absurd size
    scene_mismatch,       ///< the world to replay is not the one recorded (definition hash)
    needs_rules,          ///< made with game rules (Recording::rules_name) the reader lacks
  };
  RecordingError(Kind kind, const std::string& file, std::size_t line, std::string_view field,
                 std::string_view message);
  [[nodiscard]] Kind kind() const { return kind_; }
  [[nodiscard]] std::size_t line() const { return line_; }  ///< 1-based; 0 = not a line's fault

 private:
  Kind kind_;
  std::size_t line_;
};

/// "unreadable", "foreign", ... for messages and tests.
[[nodiscard]] std::string_view recording_error_name(RecordingError::Kind kind);

/// The recording as text (the file format; docs/CLI.md, "Recording and replay"). Throws
/// std::invalid_argument for a scene path holding a control character (it would break its line) or
/// a scene_text longer than max_recording_scene_bytes.
[[nodiscard]] std::string format_recording(const Recording& rec);
/// Parses the text of a recording; `source_name` is used in messages. Throws RecordingError:
/// foreign, unsupported_version, truncated (no `end` line, or a last line without its newline,
/// or an embedded scene cut short) or corrupt (a malformed line, a button bit outside
/// all_buttons, a non-finite number, ticks out of order, a hash beyond the end, more than
/// max_recording_ticks or max_recording_bytes, an embedded scene larger than
/// max_recording_scene_bytes or whose bytes do not match its checksum), naming the line and
/// field.
[[nodiscard]] Recording parse_recording(std::string_view text, const std::string& source_name);
/// Throws RecordingError (corrupt, naming `file` and the field) when an input of `rec` names a
/// body (drag, force, impulse, velocity) that a world made from a definition of `bodies`
/// bodies does not have: for worlds whose bodies are not created or destroyed during the run
/// (scene files), whose handles are defined_bodies() of a world of `bodies` bodies; and likewise
/// when a joint input names a joint such a world of `joints` joints does not have
/// (defined_joints()). Called before replaying, so such a recording is a bad recording, not a
/// diverged replay.
void check_recorded_bodies(const Recording& rec, std::size_t bodies, std::size_t joints,
                           const std::string& file);
/// Throws RecordingError needs_rules, naming `file` and the rules, when `rec` was made with
/// game rules (Recording::rules_name): a program that replays physics alone (`fixstep
/// replay`, `render --replay`, the web page) would step a different game.
void check_physics_only(const Recording& rec, const std::string& file);
/// Writes format_recording(rec) to `file` atomically (a temporary file beside it, then a
/// rename): `file` is never left partial. Throws std::runtime_error naming the file and the
/// system's reason when it cannot.
void write_recording(const std::filesystem::path& file, const Recording& rec);
/// Reads a recording file: RecordingError unreadable (cannot open, a directory, read error),
/// else as parse_recording.
[[nodiscard]] Recording read_recording(const std::filesystem::path& file);

/// Builds def's world (World(def)) and replays `rec` on it with `rules` (recording.hpp's
/// replay). Throws
/// RecordingError scene_mismatch naming both hashes when definition_hash(def) is not the
/// recording's (apply rec.settings to the scene first: apply_settings).
[[nodiscard]] ReplayReport replay(const WorldDef& def, const Recording& rec,
                                  const TickRules& rules = {});
}  // namespace fixstep
