// What the MP4 and GIF containers can store, checked before a video is opened: its frame size
// and its frame rate (a frame's duration in the container's units). A program checks its
// options with video_limit_error and names its own flag; VideoWriter refuses the same.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "fixstep/capture/video.hpp"

namespace fixstep {

/// The largest term of the fraction a frame rate is stored as (num / den frames per second).
inline constexpr int max_video_rate_term = 1001000;

/// The lowest GIF frame rate (frames/s): a GIF stores each frame's delay as a 16-bit count of
/// 1/100 s (GIF89a, Graphic Control Extension), so a frame lasts at most 655.35 s; FFmpeg's GIF
/// muxer clamps longer delays to that without a word.
inline constexpr double min_gif_fps = 100.0 / 65535.0;

/// A frame rate as the fraction a video stores: num / den frames per second.
struct VideoRate {
  int num = 0;
  int den = 1;
};

/// `fps` as that fraction: exact for whole numbers up to max_video_rate_term, else the closest
/// with terms up to it (av_d2q: 29.97 -> 2997/100, 30000.0 / 1001 -> 30000/1001), accepted
/// when within 1e-6 (relative) of `fps`. std::nullopt when there is none, or `fps` is not a
/// finite number > 0.
[[nodiscard]] std::optional<VideoRate> video_rate(double fps);

/// The MP4 track's timescale (ticks per second) for a video at `rate`, as FFmpeg's MP4 muxer
/// sets it (libavformat/movenc.c, mov_init): the time base's denominator (rate.num), doubled
/// until it is at least 10000.
[[nodiscard]] std::int64_t mp4_timescale(VideoRate rate);

/// The parameter of a video that a limit applies to.
enum class VideoParameter {
  size,  ///< width x height in pixels
  fps,   ///< frames per second
};

/// A parameter its container cannot store. `text` begins with the value ("321x180 is odd:
/// ...", "0.001 is too low for GIF: ..."): the caller puts the parameter's name first
/// ("frame size ", "fps ", or its own option: "--size ", "--fps ").
struct VideoLimitError {
  VideoParameter parameter;
  std::string text;
};

/// The first limit a video of `format` at width x height pixels and `fps` frames per second
/// breaks, or std::nullopt:
/// - size: MP4 (H.264 in yuv420p) needs an even width and height of at least 2; GIF 1 to
///   65535 pixels a side (16-bit fields);
/// - fps: a finite number > 0 with a fraction (video_rate); MP4 stores a frame's duration in
///   ticks of its track's timescale (mp4_timescale), and FFmpeg's MP4 muxer refuses a
///   duration of 2^31 - 1 ticks or more (movenc.c, check_pkt: "Application provided duration
///   ... is invalid") and a presentation offset (pts - dts: up to 1 + 16 B-frames = 17 frame
///   durations) over 2^31 - 1 ("pts/dts pair unsupported"): a frame may last at most
///   (2^31 - 1) / 17 ticks (at rate 1/N, timescale 16384: 7710 s); GIF at least min_gif_fps
///   (faster than max_gif_fps, frames are thinned, not refused).
[[nodiscard]] std::optional<VideoLimitError> video_limit_error(VideoFormat format, int width,
                                                               int height, double fps);

}  // namespace fixstep
