// Writing a whole file so that it is never left partial: recordings (write_recording) and
// scene files (write_scene).
#pragma once

#include <filesystem>
#include <string_view>

namespace fixstep {

/// Writes `text` to `file` atomically: into a temporary file beside it (".NAME.tmp.PID"), then
/// renamed over it, so `file` holds either its old contents or all of `text`, and the temporary
/// file is removed on failure. Throws std::runtime_error "cannot write FILE: REASON" with the
/// system's reason (e.g. "Permission denied"), or naming the directory when it does not exist.
void write_file_atomically(const std::filesystem::path& file, std::string_view text);

}  // namespace fixstep
