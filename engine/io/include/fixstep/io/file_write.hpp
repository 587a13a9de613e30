// Writing a whole file so that it is never left partial: recordings (write_recording) and
// scene files (write_scene).
#pragma once

#include <filesystem>
#include <string_view>

namespace fixstep {

/// Writes `text` to `file` through one AtomicOutput (atomic_output.hpp): a regular file or a new
/// name (a symbolic link: its final target) atomically, into a temporary file beside it
/// (".NAME.tmp.PID") renamed over it, so it holds either its old contents or all of `text`, and
/// the temporary file is removed on failure; a FIFO, a device or standard output ("-") is
/// streamed to; a directory, block device or socket is refused. Throws std::runtime_error
/// "cannot write FILE: REASON" with the system's reason (e.g. "Permission denied", "File too
/// large"), or naming the directory when it does not exist.
void write_file_atomically(const std::filesystem::path& file, std::string_view text);

}  // namespace fixstep
