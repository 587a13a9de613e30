// Internal to fixstep::app: a game's `--out DIR` (headless --frames, or --replay with --every K):
// its frames as PNGs named by frame index, and DIR/frames.csv, a row per frame written.
#pragma once

#include <cstdint>
#include <filesystem>
#include <fixstep/capture/capture.hpp>
#include <fixstep/capture/capture_dir.hpp>
#include <fixstep/capture/manifest.hpp>

#include "fixstep/app/session.hpp"

namespace fixstep::app::detail {

/// The capture into one directory: frame f is DIR/frame_path(f) (every K-th frame keeps its
/// own index: frame_000000.png, frame_000003.png, ... for K = 3), and DIR/frames.csv
/// (FrameManifest: frame, tick, t, alpha, state_hash, energy, balance) lists the frames
/// written, put under its name by finish().
class GameCapture {
 public:
  /// Prepares `dir` (prepare_capture_dir: created if missing, an old capture removed with
  /// `overwrite`) for frames of width x height px. Throws CaptureError.
  GameCapture(const std::filesystem::path& dir, bool overwrite, int width, int height)
      : writer_(prepared(dir, overwrite), width, height), manifest_(dir) {}

  /// Writes the frame `session` just drew as frame index `frame` (past the last one added),
  /// with its row. Throws CaptureError from the writer's thread, std::invalid_argument for an
  /// index not past the last.
  void add(std::uint64_t frame, const Session& session) {
    writer_.submit(session.renderer().pixels(), frame);
    manifest_.add(frame, {session.simulation(), session.alpha(), session.initial_energy()});
  }

  /// Every frame added on disk, then frames.csv under its name. Throws CaptureError.
  void finish() {
    writer_.finish();
    manifest_.commit();
  }

 private:
  static const std::filesystem::path& prepared(const std::filesystem::path& dir, bool overwrite) {
    prepare_capture_dir(dir, overwrite);
    return dir;
  }
  FrameWriter writer_;
  FrameManifest manifest_;
};

}  // namespace fixstep::app::detail
