// The containers' limits on a video's size and frame rate (video_limits.hpp).
#include "fixstep/capture/video_limits.hpp"

#include <fmt/format.h>

#include <climits>
#include <cmath>

#include "video_av.hpp"

namespace fixstep {

namespace {

constexpr int max_gif_side = 65535;  // GIF stores sizes in 16 bits
// MP4 stores a frame's presentation offset (pts - dts, ctts) in 31 bits: FFmpeg's muxer
// refuses more ("pts/dts pair unsupported"). With B-frames a frame is shown up to 1 + the
// number of B-frames later than it is decoded; x264 allows at most 16 (X264_BFRAME_MAX), so a
// frame may last at most INT_MAX / 17 ticks whatever the settings. Measured with the default
// settings (2 B-frames): 3 frames of 16384 * 43690 ticks pass, of 16384 * 43691 fail.
constexpr std::int64_t max_mp4_reorder = 17;
constexpr std::int64_t max_mp4_frame_ticks = INT_MAX / max_mp4_reorder;

std::optional<VideoLimitError> size_error(VideoFormat format, int width, int height) {
  const auto error = [](std::string text) {
    return VideoLimitError{VideoParameter::size, std::move(text)};
  };
  if (format == VideoFormat::gif) {
    if (width >= 1 && height >= 1 && width <= max_gif_side && height <= max_gif_side) return {};
    return error(fmt::format("{}x{} is outside 1x1..{}x{} (GIF's limits)", width, height,
                             max_gif_side, max_gif_side));
  }
  if (width < 2 || height < 2) {
    return error(
        fmt::format("{}x{} is below 2x2, the smallest H.264 frame in yuv420p", width, height));
  }
  if (width % 2 == 0 && height % 2 == 0) return {};
  return error(fmt::format(
      "{}x{} is odd: MP4 (H.264 in yuv420p, the pixel format every player plays) stores colour "
      "per 2x2 pixel block and needs an even width and height (e.g. {}x{})",
      width, height, width + width % 2, height + height % 2));
}

// A frame's duration in the MP4 track's ticks: at most max_mp4_frame_ticks. Without a fraction
// (`rate` empty: fps below 1/max_video_rate_term, or none close enough) the timescale of rate 1/N.
std::optional<VideoLimitError> mp4_fps_error(double fps, std::optional<VideoRate> rate) {
  const std::int64_t scale = mp4_timescale(rate.value_or(VideoRate{1, 1}));
  const double ticks =
      rate ? double(av::ffmpeg().av_rescale(scale, rate->den, rate->num)) : double(scale) / fps;
  if (ticks <= double(max_mp4_frame_ticks)) return {};
  return VideoLimitError{
      VideoParameter::fps,
      fmt::format("{:g} is too low for MP4: a frame of {:g} s is {:.0f} ticks of the track's "
                  "timescale (1/{} s), and the MP4 container stores a frame's presentation "
                  "offset, up to 17 frames with H.264's B-frames, in 31 bits: at most {} ticks "
                  "a frame (at this timescale: fps >= {:.3g})",
                  fps, 1.0 / fps, ticks, scale, max_mp4_frame_ticks,
                  double(scale) / double(max_mp4_frame_ticks) * 1.001)};
}

std::optional<VideoLimitError> gif_fps_error(double fps) {
  if (fps >= min_gif_fps) return {};
  return VideoLimitError{
      VideoParameter::fps,
      fmt::format("{:g} is too low for GIF: a frame would last {:g} s, and the GIF container "
                  "stores a frame's delay as a 16-bit count of 1/100 s, at most 655.35 s "
                  "(fps >= 0.001526)",
                  fps, 1.0 / fps)};
}

}  // namespace

std::optional<VideoRate> video_rate(double fps) {
  if (!std::isfinite(fps) || fps <= 0.0) return std::nullopt;
  if (fps == std::floor(fps) && fps <= max_video_rate_term) {
    return VideoRate{static_cast<int>(fps), 1};
  }
  const AVRational r = av::ffmpeg().av_d2q(fps, max_video_rate_term);
  if (r.num <= 0 || r.den <= 0 || r.num > max_video_rate_term || r.den > max_video_rate_term ||
      std::abs(av_q2d(r) - fps) > 1e-6 * fps) {
    return std::nullopt;
  }
  return VideoRate{r.num, r.den};
}

std::int64_t mp4_timescale(VideoRate rate) {
  std::int64_t scale = rate.num;
  while (scale < 10000) scale *= 2;
  return scale;
}

std::optional<VideoLimitError> video_limit_error(VideoFormat format, int width, int height,
                                                 double fps) {
  if (auto e = size_error(format, width, height)) return e;
  if (!std::isfinite(fps) || fps <= 0.0) {
    return VideoLimitError{VideoParameter::fps, fmt::format("{} is not a finite number > 0", fps)};
  }
  const std::optional<VideoRate> rate = video_rate(fps);
  if (format == VideoFormat::gif) {
    if (auto e = gif_fps_error(fps)) return e;
  } else if (auto e = mp4_fps_error(fps, rate)) {
    return e;
  }
  if (rate) return std::nullopt;
  if (fps > max_video_rate_term) {
    return VideoLimitError{
        VideoParameter::fps,
        fmt::format("{:g} is above {}, the highest frame rate a video stores here (as a "
                    "fraction with terms up to {})",
                    fps, max_video_rate_term, max_video_rate_term)};
  }
  return VideoLimitError{VideoParameter::fps,
                         fmt::format("{} has no fraction with terms up to {} within 1e-6 of it",
                                     fps, max_video_rate_term)};
}

}  // namespace fixstep
