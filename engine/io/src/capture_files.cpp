// The files of a capture directory (fixstep/io/capture_files.hpp).
#include "fixstep/io/capture_files.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <system_error>

namespace fixstep {

bool is_capture_file(std::string_view name) {
  if (name == "frames.csv" || name == "compare.csv") return true;
  constexpr std::string_view prefix = "frame_", suffix = ".png";
  if (!name.starts_with(prefix) || !name.ends_with(suffix)) return false;
  const std::string_view digits = name.substr(prefix.size(), name.size() - 10);
  return digits.size() >= 6 &&
         std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; });
}

std::vector<std::filesystem::path> capture_files_in(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> files;
  std::error_code ec;
  std::filesystem::directory_iterator it(dir, ec);
  for (const std::filesystem::directory_iterator end; !ec && it != end; it.increment(ec)) {
    // Regular files (or links to them) only: a directory named frame_000005.png is no frame.
    std::error_code type_ec;
    if (is_capture_file(it->path().filename().string()) && it->is_regular_file(type_ec)) {
      files.push_back(it->path());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::string capture_dir_refusal(const std::filesystem::path& dir, bool overwrite) {
  if (overwrite) return {};
  const std::vector<std::filesystem::path> old = capture_files_in(dir);
  if (old.empty()) return {};
  const auto frames = std::count_if(old.begin(), old.end(), [](const auto& f) {
    return f.filename().string().starts_with("frame_");
  });
  const bool has_manifest = std::any_of(old.begin(), old.end(),
                                        [](const auto& f) { return f.filename() == "frames.csv"; });
  return fmt::format(
      "--out {} already holds a capture ({} frames, {}): a new one would mix with it; give a "
      "new or empty directory, or --overwrite to remove the old capture's files first",
      dir.string(), frames,
      has_manifest ? "its frames.csv" : "no frames.csv: an unfinished or killed run");
}

}  // namespace fixstep
