// `--out DIR` of a capture (fixstep render and compare, a game's frames): one capture per
// directory, never a mix of two runs. The names a capture writes, and whether a directory
// already holds one.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace fixstep {

/// Whether `name` is a file a capture writes into its directory: frame_NNNNNN.png (six or more
/// digits), frames.csv (the manifest, renamed into place after the last frame) or compare.csv.
[[nodiscard]] bool is_capture_file(std::string_view name);

/// The regular files (or links to one) in `dir` named as capture files (is_capture_file),
/// sorted; none when it does not exist.
[[nodiscard]] std::vector<std::filesystem::path> capture_files_in(const std::filesystem::path& dir);

/// "" when a capture may go into `dir`: it does not exist, holds no capture file, or
/// `overwrite` is set. Otherwise the refusal: "--out DIR already holds a capture (N frames, its
/// frames.csv): a new one would mix with it; give a new or empty directory, or --overwrite".
/// Other files in `dir` do not count: they cannot be taken for part of the capture. Every
/// capture (fixstep render and compare, a game's --out) writes its frames.csv last, so frames
/// without one are named "an unfinished or killed run".
[[nodiscard]] std::string capture_dir_refusal(const std::filesystem::path& dir, bool overwrite);

}  // namespace fixstep
