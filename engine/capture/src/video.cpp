// VideoWriter: argument checks, the temporary file's fate and the producer/worker pipeline
// (the encoding itself is video_encoder.cpp).
#include "fixstep/capture/video.hpp"

#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string_view>
#include <utility>

#include "fixstep/capture/video_limits.hpp"
#include "fixstep/core/world_settings.hpp"
#include "fixstep/io/atomic_output.hpp"
#include "fixstep/io/write_signals.hpp"
#include "video_encoder.hpp"

namespace fixstep {

std::optional<VideoFormat> video_format_for(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".mp4") return VideoFormat::mp4;
  if (ext == ".gif") return VideoFormat::gif;
  return std::nullopt;
}

namespace {

constexpr std::array<std::string_view, 10> x264_presets = {
    "ultrafast", "superfast", "veryfast", "faster",   "fast",
    "medium",    "slow",      "slower",   "veryslow", "placebo"};
constexpr std::array<std::string_view, 9> x264_tunes = {
    "", "film", "animation", "grain", "stillimage", "psnr", "ssim", "fastdecode", "zerolatency"};
constexpr int max_video_threads = 64;

[[noreturn]] void refuse(const std::filesystem::path& file, const std::string& what) {
  throw std::invalid_argument(fmt::format("cannot write {}: {}", file.string(), what));
}

VideoFormat format_of(const std::filesystem::path& file) {
  if (const auto format = video_format_for(file)) return *format;
  refuse(file, fmt::format("unknown video format \"{}\" (use .mp4 for H.264 video or .gif for "
                           "an animated GIF)",
                           file.extension().string()));
}

/// `format` at width x height and fps within its container's limits (video_limit_error).
AVRational checked_rate(const std::filesystem::path& file, VideoFormat format, int width,
                        int height, double fps) {
  if (const auto e = video_limit_error(format, width, height, fps)) {
    refuse(file, (e->parameter == VideoParameter::size ? "frame size " : "fps ") + e->text);
  }
  const VideoRate rate = *video_rate(fps);
  return AVRational{rate.num, rate.den};
}

// GIF: keep every n-th frame so that at most max_gif_fps frames per second remain.
int frame_step_of(VideoFormat format, double fps) {
  if (format != VideoFormat::gif || fps <= max_gif_fps) return 1;
  return static_cast<int>(std::ceil(fps / max_gif_fps - 1e-9));
}

void remove_quietly(const std::filesystem::path& file) {
  std::error_code ec;
  std::filesystem::remove(file, ec);
}

}  // namespace

std::string video_settings_error(const VideoSettings& settings) {
  if (settings.crf < min_video_crf || settings.crf > max_video_crf) {
    return fmt::format("crf {} is outside {}..{} (libx264's scale: 0 = lossless, 51 = worst)",
                       settings.crf, min_video_crf, max_video_crf);
  }
  if (std::find(x264_presets.begin(), x264_presets.end(), settings.preset) == x264_presets.end()) {
    return fmt::format("preset \"{}\" is not one of libx264's: {}", settings.preset,
                       fmt::join(x264_presets, ", "));
  }
  if (std::find(x264_tunes.begin(), x264_tunes.end(), settings.tune) == x264_tunes.end()) {
    return fmt::format("tune \"{}\" is not one of libx264's: \"\" (none), {}", settings.tune,
                       fmt::join(x264_tunes.begin() + 1, x264_tunes.end(), ", "));
  }
  if (settings.threads < 0 || settings.threads > max_video_threads) {
    return fmt::format("threads {} is outside 0..{} (0: libx264 chooses)", settings.threads,
                       max_video_threads);
  }
  return {};
}

VideoWriter::VideoWriter(std::filesystem::path file, int width, int height, double fps,
                         VideoSettings settings, int in_flight)
    : file_(std::move(file)), format_(format_of(file_)), width_(width), height_(height) {
  const AVRational rate = checked_rate(file_, format_, width, height, fps);
  if (const std::string error = video_settings_error(settings); !error.empty()) {
    refuse(file_, error);
  }
  if (in_flight < 1) refuse(file_, fmt::format("in_flight is {}, must be >= 1", in_flight));
  frame_step_ = frame_step_of(format_, fps);
  frame_bytes_ = static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4;
  ignore_file_size_signal();  // a write past `ulimit -f` fails with EFBIG, reported
  target_ = classify_output(file_);
  if (target_.kind == OutputKind::refused) {
    throw CaptureError(fmt::format("cannot write {}: {}", file_.string(), output_refusal(target_)));
  }
  try {  // from here on the temporary file may exist: remove it if anything fails
    encoder_ =
        std::make_unique<Encoder>(open_destination(), file_,
                                  Encoder::Options{.format = format_,
                                                   .width = width,
                                                   .height = height,
                                                   .rate = rate,
                                                   .step = frame_step_,
                                                   .settings = std::move(settings),
                                                   .streamed = target_.kind == OutputKind::stream});
    pipeline_ = std::make_unique<FramePipeline>(
        frame_bytes_, static_cast<std::size_t>(in_flight),
        [this](std::span<const std::uint8_t> rgba, std::uint64_t pts) {
          encoder_->encode(rgba, static_cast<std::int64_t>(pts));
        },
        FramePipeline::Pending::drop);
  } catch (...) {
    encoder_.reset();
    discard();
    throw;
  }
}

std::string VideoWriter::open_destination() {
  if (target_.kind == OutputKind::stream) {
    stream_fd_ = open_output_stream(target_);
    if (stream_fd_ < 0) {
      throw CaptureError(fmt::format("cannot write {}: {}", file_.string(), std::strerror(errno)));
    }
    return fmt::format("pipe:{}", stream_fd_);  // FFmpeg writes it, never closes it
  }
  const std::filesystem::path& target = target_.path;
  const std::filesystem::path dir = target.has_parent_path() ? target.parent_path() : ".";
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) {
    throw CaptureError(fmt::format("cannot write {}: the directory {} does not exist",
                                   file_.string(), dir.string()));
  }
  tmp_ = temporary_file_for(target);
  return tmp_.string();
}

void VideoWriter::publish() {
  if (target_.kind == OutputKind::stream) {
    const int fd = std::exchange(stream_fd_, -1);
    if (::close(fd) != 0) {
      throw CaptureError(fmt::format("cannot write {}: {}", file_.string(), std::strerror(errno)));
    }
    return;
  }
  // The replaced file's permission bits (FFmpeg creates the file with the default ones).
  if (target_.mode) (void)::chmod(tmp_.c_str(), static_cast<mode_t>(*target_.mode));
  if (::rename(tmp_.c_str(), target_.path.c_str()) != 0) {
    throw CaptureError(fmt::format("cannot write {}: {}", file_.string(), std::strerror(errno)));
  }
}

void VideoWriter::discard() noexcept {
  if (stream_fd_ >= 0) ::close(std::exchange(stream_fd_, -1));
  if (!tmp_.empty()) remove_quietly(tmp_);
}

VideoWriter::~VideoWriter() {
  halt();  // frames still queued are dropped: the video is abandoned unless finished
  if (!finished_) {
    encoder_.reset();  // closes the temporary file, without a trailer
    discard();
  }
}

void VideoWriter::halt() noexcept {
  try {
    if (pipeline_) pipeline_->stop(FramePipeline::Pending::drop);
  } catch (...) {  // NOLINT(bugprone-empty-catch): submit() or finish() reported it already
  }
}

void VideoWriter::rethrow_or_finished() const {
  if (error_) std::rethrow_exception(error_);
  if (const std::exception_ptr e = pipeline_->error()) std::rethrow_exception(e);
  throw CaptureError(fmt::format("cannot write {}: the video is already finished", file_.string()));
}

void VideoWriter::submit(std::span<const std::uint8_t> rgba) {
  if (rgba.size() != frame_bytes_) {
    refuse(file_, fmt::format("frame {} has {} bytes, {}x{} RGBA8 is {}", submitted_, rgba.size(),
                              width_, height_, frame_bytes_));
  }
  if (finished_ || !pipeline_->running()) rethrow_or_finished();
  const std::uint64_t frame = submitted_++;
  if (frame % static_cast<std::uint64_t>(frame_step_) != 0) return;  // a GIF's thinned frame
  pipeline_->submit(rgba, frame);
}

void VideoWriter::finish() {
  if (finished_) return;
  if (!pipeline_->running()) rethrow_or_finished();  // a failed finish() discarded the video
  try {
    pipeline_->drain();                             // throws the encoder's error, if any
    pipeline_->stop(FramePipeline::Pending::drop);  // nothing is queued: the encoder is ours
    encoder_->finish();
    encoder_.reset();
    publish();
  } catch (...) {
    error_ = std::current_exception();  // later calls report it too
    halt();
    encoder_.reset();
    discard();
    throw;
  }
  finished_ = true;
}

}  // namespace fixstep
