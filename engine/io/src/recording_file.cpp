// Recordings as files: read_recording (only a regular file, bounded: file_read.hpp) and
// write_recording (atomic: file_write.hpp). The text itself is made and read apart from any file
// (format_recording, parse_recording: recording_format.cpp), so that a caller may keep it in a
// buffer of its own.
#include "fixstep/io/recording_file.hpp"

#include <fmt/format.h>

#include <string>
#include <system_error>

#include "fixstep/io/file_read.hpp"
#include "fixstep/io/file_write.hpp"

namespace fixstep {

namespace {

/// The message of a RecordingError for a recording read_regular_file refused.
std::string unreadable_message(const std::filesystem::path& file, const FileReadError& e) {
  switch (e.kind()) {
    case FileReadError::Kind::missing: {
      std::error_code ec;
      const bool no_dir =
          file.has_parent_path() && !std::filesystem::is_directory(file.parent_path(), ec);
      return no_dir ? fmt::format("no such recording: the directory {} does not exist",
                                  file.parent_path().string())
                    : std::string("no such recording");
    }
    case FileReadError::Kind::not_regular: {
      const std::string type = file_type_of(file);
      if (type == "a directory") return "is a directory, not a recording";
      if (type.empty()) return e.reason();
      return fmt::format(
          "is {}, not a recording: only a regular file is read (a FIFO or a device could block "
          "or never end)",
          type);
    }
    case FileReadError::Kind::too_large:
      return fmt::format("larger than the {} bytes a recording may have", max_recording_bytes);
    case FileReadError::Kind::unreadable:
      break;
  }
  return e.reason().starts_with("read error")
             ? e.reason()
             : fmt::format("cannot open the recording: {}", e.reason());
}

}  // namespace

Recording read_recording(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::string text;
  try {
    text = read_regular_file(file, max_recording_bytes);
  } catch (const FileReadError& e) {
    throw RecordingError(e.kind() == FileReadError::Kind::too_large
                             ? RecordingError::Kind::corrupt
                             : RecordingError::Kind::unreadable,
                         name, 0, "", unreadable_message(file, e));
  }
  return parse_recording(text, name);
}

void write_recording(const std::filesystem::path& file, const Recording& rec) {
  write_file_atomically(file, format_recording(rec));
}

}  // namespace fixstep
