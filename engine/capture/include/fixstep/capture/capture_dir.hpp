// A capture directory made ready for a new capture (fixstep render and compare, a game's
// `--out DIR`): which files are a capture's, and the refusal of a directory that holds one, are
// fixstep/io/capture_files.hpp's.
#pragma once

#include <filesystem>

namespace fixstep {

/// Prepares `dir` for a new capture: creates it if missing (prepare_output_dir; CaptureError),
/// removes the stale temporaries of capture files left by killed runs, and with `overwrite`
/// removes the old capture's files, frames.csv first (so an interrupted removal never leaves a
/// manifest naming frames that are gone). Files that are not capture files are left alone.
/// Throws CaptureError naming a file that cannot be removed.
void prepare_capture_dir(const std::filesystem::path& dir, bool overwrite);

}  // namespace fixstep
