// `fixstep compare`: one scene under several integrators and steps at once, tiled in one frame.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"

namespace fixstep::cli {

struct CompareOptions {
  std::string scene;
  std::vector<std::string> with;       ///< --with specs (compare_tiles.hpp, TileSpec), 2..6
  std::optional<std::string> out;      ///< --out DIR: PNG frames, frames.csv, compare.csv
  std::optional<std::string> video;    ///< --video FILE.mp4|.gif
  std::optional<std::string> csv;      ///< --csv FILE: the summary, a row per tile
  bool window = false;                 ///< --window: show it live (also without --out/--video)
  std::optional<std::int64_t> frames;  ///< captures: default 240; window: until Esc
  std::optional<double> fps;           ///< captures: default 60; window: virtual clock
  std::string size = "1280x720";
  int png_level = default_png_level;
  bool allow_unstable = false;
  bool quiet = false;
  bool overwrite = false;  ///< --overwrite: remove the old capture's files in --out DIR first
  std::optional<std::string> joints;  ///< --joints off|anchors|limits: overrides [view] joints
};

/// Frames of a capture when --frames is not given (4 s at 60 frames/s).
inline constexpr std::int64_t default_compare_frames = 240;

/// The summary CSV's path: --csv, else DIR/compare.csv beside the PNGs, else
/// NAME.EXT.compare.csv beside the video NAME.EXT (beside_video: none for a streamed video);
/// none for a window without --csv.
[[nodiscard]] std::optional<std::filesystem::path> summary_path(const CompareOptions& o);

int compare_command(const CompareOptions& options);

}  // namespace fixstep::cli
