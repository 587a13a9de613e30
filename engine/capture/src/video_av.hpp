// Owning handles for FFmpeg's C objects and its error codes as CaptureErrors (internal to
// fixstep::render's video capture: video_encoder.cpp, video_palette.cpp).
#pragma once

#include <fmt/format.h>

#include <filesystem>
#include <memory>
#include <string>

#include "ffmpeg_library.hpp"
#include "fixstep/capture/capture.hpp"

namespace fixstep::av {

struct FrameFree {
  void operator()(AVFrame* f) const { ffmpeg().av_frame_free(&f); }
};
struct PacketFree {
  void operator()(AVPacket* p) const { ffmpeg().av_packet_free(&p); }
};
struct CodecFree {
  void operator()(AVCodecContext* c) const { ffmpeg().avcodec_free_context(&c); }
};
struct SwsFree {
  void operator()(SwsContext* s) const { ffmpeg().sws_freeContext(s); }
};
struct MuxerFree {  // closes the file if open, then frees the muxer and its streams
  void operator()(AVFormatContext* m) const {
    if (m->pb) ffmpeg().avio_closep(&m->pb);
    ffmpeg().avformat_free_context(m);
  }
};
struct GraphFree {
  void operator()(AVFilterGraph* g) const { ffmpeg().avfilter_graph_free(&g); }
};
using Frame = std::unique_ptr<AVFrame, FrameFree>;
using Packet = std::unique_ptr<AVPacket, PacketFree>;
using Codec = std::unique_ptr<AVCodecContext, CodecFree>;
using Sws = std::unique_ptr<SwsContext, SwsFree>;
using Muxer = std::unique_ptr<AVFormatContext, MuxerFree>;
using Graph = std::unique_ptr<AVFilterGraph, GraphFree>;

/// FFmpeg's message for error code `err` (a negative AVERROR).
inline std::string error_text(int err) {
  char buf[AV_ERROR_MAX_STRING_SIZE] = {};
  ffmpeg().av_strerror(err, buf, sizeof buf);
  return buf;
}

/// CaptureError "cannot write FILE: WHAT: FFmpeg's reason".
[[noreturn]] inline void fail(const std::filesystem::path& file, const std::string& what, int err) {
  throw CaptureError(fmt::format("cannot write {}: {}: {}", file.string(), what, error_text(err)));
}

/// Throws as fail() when `err` < 0; returns `err` otherwise.
inline int check(int err, const std::filesystem::path& file, const std::string& what) {
  if (err < 0) fail(file, what, err);
  return err;
}

/// A frame of `format` at width x height with its own buffers (32-byte aligned rows).
/// Throws CaptureError naming `file` when FFmpeg cannot allocate it.
inline Frame make_frame(AVPixelFormat format, int width, int height,
                        const std::filesystem::path& file) {
  Frame f(ffmpeg().av_frame_alloc());
  if (!f) throw CaptureError(fmt::format("cannot write {}: out of memory", file.string()));
  f->format = format;
  f->width = width;
  f->height = height;
  check(ffmpeg().av_frame_get_buffer(f.get(), 32), file, "cannot allocate a frame");
  return f;
}

}  // namespace fixstep::av
