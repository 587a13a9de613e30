// Where a headless command's frames go: a PNG sequence in a directory, a video file, or both,
// each with its frames.csv manifest beside it. Shared by `render` and `compare`.
#pragma once

#include <cstdint>
#include <filesystem>
#include <fixstep/app/session.hpp>
#include <fixstep/capture/capture.hpp>
#include <fixstep/capture/manifest.hpp>
#include <fixstep/capture/video.hpp>
#include <optional>
#include <span>
#include <string>

namespace fixstep::cli {

struct CaptureTargets {
  std::optional<std::string> out;    ///< directory of frame_NNNNNN.png (created if missing)
  std::optional<std::string> video;  ///< a .mp4 (H.264) or .gif file
  int png_level = default_png_level;
  bool overwrite = false;  ///< --overwrite: the old capture's files in `out` are removed first
};

/// "give --out DIR or --video FILE (.mp4 or .gif)" when neither is set, or the video's
/// extension is not one VideoWriter writes; "" when the targets are usable.
[[nodiscard]] std::string capture_targets_error(const CaptureTargets& targets);

/// "--size 321x180 is odd: ..." or "--fps 0.001 is too low for GIF: ..." when a video of
/// width x height at `fps` breaks its container's limits (video_limit_error), naming the
/// option to change; "" when it does not or there is no video.
[[nodiscard]] std::string video_options_error(const std::optional<std::string>& video, int width,
                                              int height, double fps);

/// The file written beside the video `video`: VIDEO + `suffix` (".frames.csv": the manifest;
/// ".compare.csv": compare's summary). None when the video is streamed (a FIFO, a device,
/// standard output): there is no directory of its own to write into, and a device's is /dev.
[[nodiscard]] std::optional<std::filesystem::path> beside_video(const std::string& video,
                                                                const char* suffix);

class CaptureSink {
 public:
  /// Prepares the directory (prepare_capture_dir: created, stale temporaries and with
  /// `overwrite` the old capture removed) and opens the writers and manifests: PNG frames
  /// through a FrameWriter, the video through a VideoWriter at `fps`, both encoding on worker
  /// threads. Throws CaptureError naming the path that cannot be written, std::invalid_argument
  /// for a size the video cannot take.
  CaptureSink(const CaptureTargets& targets, int width, int height, double fps,
              ManifestLayout layout);

  /// Queues a frame (height rows of width RGBA8 pixels, top row first) for every target.
  void submit(std::span<const std::uint8_t> rgba);
  /// The manifest row(s) of the frame last submitted, drawn by `session` (frames layout).
  void add_row(std::uint64_t frame, const Session& session);
  /// The row of tile `tile` (as its HUD numbers it) of the frame last submitted (tiles layout).
  void add_row(std::uint64_t frame, std::size_t tile, const Session& session);
  /// Waits for every frame to be written, then puts the video and the manifests under their
  /// names. Throws the first CaptureError of a writer.
  void finish();

  /// Prints where everything went: "frames=N ... : first ... last", "video=FILE", "manifest=..."
  /// lines for `frames` frames written of width x height at fps.
  void print_paths(std::uint64_t frames, const std::string& note) const;

 private:
  CaptureTargets targets_;
  int width_, height_;
  double fps_;
  std::optional<FrameWriter> png_;
  std::optional<VideoWriter> video_;
  std::optional<FrameManifest> png_manifest_, video_manifest_;
};

}  // namespace fixstep::cli
