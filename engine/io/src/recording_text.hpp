// The lines of a recording file, shared by format_recording (recording_format.cpp) and the
// streaming RecordingWriter (recording_writer.cpp), so both write the same bytes. Internal to
// the engine: not installed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "fixstep/core/input.hpp"
#include "fixstep/io/recording_file.hpp"

namespace fixstep::recording_text {

/// The header: "fixstep-recording VERSION" through "hash_every K", each line ending in '\n',
/// with the embedded scene's section (append_scene_text) after the `scene` line when
/// rec.scene_text is not empty. Throws std::invalid_argument for a scene path holding a
/// control character or a scene_text longer than max_recording_scene_bytes.
[[nodiscard]] std::string header(const Recording& rec);
/// Appends "tick N push=... drag=... [per-body inputs]\n".
void append_tick(std::string& out, const TickInput& input);
/// Appends "hash N HASH\n".
void append_hash(std::string& out, std::uint64_t tick, std::uint64_t hash);
/// Appends "end TICKS HASH\n".
void append_end(std::string& out, std::uint64_t ticks, std::uint64_t hash);

/// FNV-1a (64-bit) of `text`'s bytes: the embedded scene's checksum.
[[nodiscard]] std::uint64_t scene_checksum(std::string_view text);
/// Appends the embedded scene's section: "scene_text BYTES CHECKSUM\n", then each line of
/// `text` as "|LINE\n" with '\\', '\r' and other control characters but the tab escaped
/// (recording_scene_text.cpp). Throws std::invalid_argument beyond max_recording_scene_bytes.
void append_scene_text(std::string& out, std::string_view text);

/// Reads the lines of an embedded scene's section back into its bytes, one line at a time.
class SceneTextDecoder {
 public:
  /// For a section of `bytes` bytes (1 .. max_recording_scene_bytes, which the caller checks:
  /// that much is reserved) whose bytes hash to `checksum`.
  SceneTextDecoder(std::size_t bytes, std::uint64_t checksum);
  /// Takes the next "|LINE" line (without its newline); returns "" or what is wrong with it
  /// (not a scene line, a bad escape, a raw control character, more bytes than declared).
  [[nodiscard]] std::string take(std::string_view line);
  /// Whether the lines taken hold the declared bytes (the section is complete).
  [[nodiscard]] bool done() const { return text_.size() >= bytes_; }
  /// Once done(): moves the scene's bytes into `text` and returns "", or returns the message
  /// for bytes that do not match the checksum (`text` untouched).
  [[nodiscard]] std::string finish(std::string& text);
  /// Bytes read so far.
  [[nodiscard]] std::size_t size() const { return text_.size(); }

 private:
  std::size_t bytes_;
  std::uint64_t checksum_;
  std::string text_;
};

}  // namespace fixstep::recording_text
