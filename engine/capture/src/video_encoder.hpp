// The encoding half of VideoWriter: codec + muxer writing one file (internal to
// fixstep::render; video.cpp owns the pipeline and the temporary file's fate).
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>

#include "fixstep/capture/video.hpp"
#include "video_av.hpp"
#include "video_palette.hpp"
#include "video_yuv.hpp"

namespace fixstep {

/// Encodes RGBA8 frames into FFmpeg's `url` (the temporary file's path, or "pipe:FD" for a
/// stream; errors name `file`, the name the user gave): MP4 through YuvConverter + libx264, GIF
/// through GifPalette + FFmpeg's GIF encoder. Frame k has pts k in the time base 1 / `rate` (s) and
/// lasts `step` ticks. Destroyed without finish(), it closes the file as it is (no trailer); the
/// caller removes it. Not thread-safe: one thread at a time (VideoWriter hands it from its worker
/// to the caller of finish() only after joining the worker).
class VideoWriter::Encoder {
 public:
  struct Options {
    VideoFormat format = VideoFormat::mp4;
    int width = 0, height = 0;  ///< pixels
    AVRational rate{0, 1};      ///< frames per second as a fraction
    int step = 1;               ///< ticks of 1/rate each encoded frame lasts
    VideoSettings settings;
    bool streamed = false;  ///< `url` cannot seek: MP4 is fragmented, not +faststart
  };
  /// Opens the codec, the muxer and `url`, and writes the container header. Throws
  /// CaptureError naming `file` (missing encoder or filter, unwritable path, refused stream).
  Encoder(const std::string& url, const std::filesystem::path& file, const Options& options);
  ~Encoder();
  Encoder(const Encoder&) = delete;
  Encoder& operator=(const Encoder&) = delete;

  /// Encodes `rgba` (width*height*4 bytes) as the frame with pts `pts` and writes the packets
  /// the encoder returns. Throws CaptureError naming the file.
  void encode(std::span<const std::uint8_t> rgba, std::int64_t pts);
  /// Drains the encoder (and the palette filter), writes the trailer and closes the file.
  /// Throws CaptureError naming the file.
  void finish();

 private:
  void open_codec(const Options& options);
  void open_file(const std::string& url, const Options& options);
  void send(const AVFrame* frame);  // nullptr: flush
  void write_packets();
  void drain_palette();
  void set_gif_final_delay();

  std::filesystem::path file_;
  int step_ = 1;
  std::int64_t last_pts_ = -1;  // pts of the last frame sent to the codec, -1: none yet
  bool header_written_ = false, trailer_written_ = false;
  av::Muxer mux_;               // owns its AVIOContext once the file is open
  AVStream* stream_ = nullptr;  // owned by mux_
  av::Codec codec_;
  av::Packet packet_;
  av::Frame paletted_;  // GIF: the palette filter's output frame
  std::optional<av::YuvConverter> yuv_;
  std::optional<av::GifPalette> palette_;
};

}  // namespace fixstep
