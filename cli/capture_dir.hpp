// `--out DIR` of render and compare: one capture per directory, never a mix of two runs.
#pragma once

#include <filesystem>
#include <string_view>
#include <vector>

namespace fixstep::cli {

/// Whether `name` is a file a capture writes into its directory: frame_NNNNNN.png (six or more
/// digits), frames.csv (the manifest, renamed into place after the last frame) or compare.csv.
[[nodiscard]] bool is_capture_file(std::string_view name);

/// The regular files (or links to one) in `dir` named as capture files (is_capture_file),
/// sorted; none when it does not exist.
[[nodiscard]] std::vector<std::filesystem::path> capture_files_in(const std::filesystem::path& dir);

/// "" when a capture may go into `dir`: it does not exist, holds no capture file, or
/// `overwrite` is set. Otherwise the refusal: "--out DIR already holds a capture (N frames, its
/// frames.csv): a new one would mix with it; give a new or empty directory, or --overwrite".
/// Other files in `dir` do not count: they cannot be taken for part of the capture.
[[nodiscard]] std::string capture_dir_refusal(const std::filesystem::path& dir, bool overwrite);

/// Prepares `dir` for a new capture: creates it if missing (prepare_output_dir; CaptureError),
/// removes the stale temporaries of capture files left by killed runs, and with `overwrite`
/// removes the old capture's files, frames.csv first (so an interrupted removal never leaves a
/// manifest naming frames that are gone). Files that are not capture files are left alone.
/// Throws CaptureError naming a file that cannot be removed.
void prepare_capture_dir(const std::filesystem::path& dir, bool overwrite);

}  // namespace fixstep::cli
