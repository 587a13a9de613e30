#include "capture_sink.hpp"

#include <fmt/format.h>

#include <fixstep/capture/capture_dir.hpp>
#include <fixstep/capture/video_limits.hpp>
#include <fixstep/io/output_target.hpp>

namespace fixstep::cli {

std::string capture_targets_error(const CaptureTargets& t) {
  if (!t.out && !t.video) return "give --out DIR (PNG frames) or --video FILE (.mp4 or .gif)";
  if (t.video && !video_format_for(*t.video) && classify_output(*t.video).fd >= 0) {
    return fmt::format(
        "--video {}: a video's format comes from its name's extension (.mp4 or .gif), and {} "
        "has none: to pipe a video, make a FIFO with such a name (mkfifo clip.mp4) and read it",
        *t.video, classify_output(*t.video).what);
  }
  if (t.video && !video_format_for(*t.video)) {
    return fmt::format("--video {}: the file name must end in .mp4 (H.264) or .gif", *t.video);
  }
  return {};
}

std::string video_options_error(const std::optional<std::string>& video, int width, int height,
                                double fps) {
  const std::optional<VideoFormat> format = video ? video_format_for(*video) : std::nullopt;
  if (!format) return {};
  const auto e = video_limit_error(*format, width, height, fps);
  if (!e) return {};
  return fmt::format("{} {} (--video {})",
                     e->parameter == VideoParameter::size ? "--size" : "--fps", e->text, *video);
}

std::optional<std::filesystem::path> beside_video(const std::string& video, const char* suffix) {
  if (classify_output(video).kind == OutputKind::stream) return std::nullopt;
  std::filesystem::path p = video;
  return p += suffix;
}

CaptureSink::CaptureSink(const CaptureTargets& targets, int width, int height, double fps,
                         ManifestLayout layout)
    : targets_(targets), width_(width), height_(height), fps_(fps) {
  if (targets_.out) {
    prepare_capture_dir(*targets_.out, targets_.overwrite);
    png_.emplace(*targets_.out, width, height, PngSettings{.level = targets_.png_level});
    png_manifest_.emplace(std::filesystem::path(*targets_.out) / "frames.csv", layout);
  }
  if (targets_.video) {
    video_.emplace(*targets_.video, width, height, fps);
    if (const auto manifest = beside_video(*targets_.video, ".frames.csv")) {
      video_manifest_.emplace(*manifest, layout);
    }
  }
}

void CaptureSink::submit(std::span<const std::uint8_t> rgba) {
  if (png_) png_->submit(rgba);
  if (video_) video_->submit(rgba);
}

namespace {
FrameState frame_state(const Session& session) {
  return {session.simulation(), session.alpha(), session.initial_energy()};
}
}  // namespace

void CaptureSink::add_row(std::uint64_t frame, const Session& session) {
  if (png_manifest_) png_manifest_->add(frame, frame_state(session));
  if (video_manifest_) video_manifest_->add(frame, frame_state(session));
}

void CaptureSink::add_row(std::uint64_t frame, std::size_t tile, const Session& session) {
  if (png_manifest_) png_manifest_->add(frame, tile, frame_state(session));
  if (video_manifest_) video_manifest_->add(frame, tile, frame_state(session));
}

void CaptureSink::finish() {
  if (png_) png_->finish();  // every frame on disk, or the first failure's CaptureError
  if (video_) video_->finish();
  if (png_manifest_) png_manifest_->commit();
  if (video_manifest_) video_manifest_->commit();
}

void CaptureSink::print_paths(std::uint64_t frames, const std::string& note) const {
  if (png_ && frames > 0) {
    fmt::print("frames={}{} fps={} size={}x{}: {} ... {}\n", frames, note, fps_, width_, height_,
               frame_path(*targets_.out, 0).string(),
               frame_path(*targets_.out, frames - 1).string());
  }
  if (video_) {
    fmt::print("video={} frames={}{} fps={} size={}x{}\n", *targets_.video, frames, note, fps_,
               width_, height_);
  }
  if (png_manifest_) fmt::print("manifest={}\n", png_manifest_->file().string());
  if (video_manifest_) fmt::print("manifest={}\n", video_manifest_->file().string());
}

}  // namespace fixstep::cli
