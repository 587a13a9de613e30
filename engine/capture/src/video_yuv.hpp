// RGBA8 frames to H.264's yuv420p with libswscale (internal to the MP4 path of VideoWriter).
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>

#include "video_av.hpp"

namespace fixstep::av {

/// The colour tags of the frames YuvConverter makes: BT.709 primaries, transfer and matrix,
/// limited ("MPEG", 16..235) range. Written into the stream so players convert back alike.
void tag_bt709_limited(AVCodecContext& codec);

/// Converts width x height RGBA8 images (sRGB, full range, top row first, width*4 bytes per
/// row; alpha ignored) into one reused yuv420p AVFrame: the BT.709 matrix, limited range,
/// chroma at half resolution (libswscale, SWS_POINT: video_yuv.cpp has the measurements that
/// chose it). Allocates only when the encoder still holds the previous frame (libx264 does
/// not: it copies).
class YuvConverter {
 public:
  /// Throws CaptureError naming `file` when libswscale or the frame cannot be set up.
  YuvConverter(int width, int height, const std::filesystem::path& file);
  /// The frame converted from `rgba` (width*height*4 bytes), with pts `pts`; owned by this
  /// converter and valid until the next call. Throws CaptureError naming the file.
  AVFrame* convert(std::span<const std::uint8_t> rgba, std::int64_t pts);

 private:
  int width_, height_;
  std::filesystem::path file_;
  Sws sws_;
  Frame frame_;
};

}  // namespace fixstep::av
