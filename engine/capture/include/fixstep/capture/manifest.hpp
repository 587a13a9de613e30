// frames.csv: the manifest written beside a capture (fixstep render and compare, a game's
// --out), one row per frame written, so a CI job can diff a run against an earlier one without
// decoding an image.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "fixstep/capture/capture.hpp"
#include "fixstep/core/world.hpp"

namespace fixstep {

/// Which rows a manifest holds: one per frame, or one per tile of each frame (`fixstep compare`,
/// whose frames show several sessions side by side; an extra column `tile` after `frame`).
enum class ManifestLayout { frames, tiles };

/// The manifest beside a video file: "clip.mp4" -> "clip.mp4.frames.csv" (same directory; the
/// extension kept, so clip.mp4 and clip.gif have a manifest each).
[[nodiscard]] std::filesystem::path video_manifest_path(const std::filesystem::path& video);

/// What a manifest row says of a frame: the world it was drawn from, the interpolation alpha it
/// was drawn at, in [0, 1), and the world's initial energy, J (for the balance column).
struct FrameState {
  const World& world;
  double alpha = 0.0;
  double initial_energy = 0.0;
};

/// frames.csv, written as the frames are (into an AtomicFile: complete under its name after
/// commit(), absent before). Columns (header line first):
///   frame       frame index (the PNG frame_NNNNNN.png, the video's frame); a capture of
///               every K-th frame (a game's --replay --every K) lists 0, K, 2K, ... and its last
///   tile        (ManifestLayout::tiles only) the tile's index, 0-based, row-major
///   tick        ticks taken when the frame was drawn
///   t           simulated time tick·dt, s (%.6f)
///   alpha       the loop's interpolation weight the frame was drawn at, in [0, 1) (%.6f)
///   state_hash  World::state_hash(), 16 hex digits (what `run`/`render` summaries print)
///   energy      total energy, J (%.9e)
///   balance     energy_balance() (%.6e; in J when the initial energy is 0)
class FrameManifest {
 public:
  /// The manifest of a capture into `dir` (which must exist: prepare_output_dir), named
  /// dir/frames.csv once commit()ted. Throws CaptureError when the file cannot be created.
  explicit FrameManifest(const std::filesystem::path& dir);
  /// The manifest named `file` itself (e.g. video_manifest_path(video)), whose directory must
  /// exist. Throws CaptureError when the file cannot be created.
  FrameManifest(std::filesystem::path file, ManifestLayout layout);

  /// Appends the row of frame `frame`, drawn from `state`. Throws CaptureError on a write
  /// error, std::logic_error in a tiles manifest. No allocation once the row buffer has grown.
  void add(std::uint64_t frame, const FrameState& state);
  /// Appends the row of tile `tile` of frame `frame` (ManifestLayout::tiles; std::logic_error
  /// in a frames manifest).
  void add(std::uint64_t frame, std::size_t tile, const FrameState& state);
  /// Puts frames.csv under its name, complete. Throws CaptureError when it cannot.
  void commit();

  [[nodiscard]] const std::filesystem::path& file() const { return path_; }

 private:
  std::filesystem::path path_;
  AtomicFile out_;
  ManifestLayout layout_;
  std::string row_;
};

}  // namespace fixstep
