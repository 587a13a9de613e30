// Reading a video file back for tests: every frame decoded with FFmpeg (libavformat,
// libavcodec) and converted to RGB24 with libswscale as a player would, plus PSNR.
#pragma once

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libswscale/swscale.h>
}

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace fixstep::testing {

using Image = std::vector<std::uint8_t>;  // RGB24, top row first

inline Image rgb_of_rgba(std::span<const std::uint8_t> rgba) {
  Image rgb;
  rgb.reserve(rgba.size() / 4 * 3);
  for (std::size_t p = 0; p < rgba.size(); p += 4) rgb.insert(rgb.end(), &rgba[p], &rgba[p + 3]);
  return rgb;
}

/// PSNR (dB) of `b` against `a` over all R, G, B samples (peak 255).
inline double psnr(const Image& a, const Image& b) {
  double se = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) se += std::pow(double(a[i]) - double(b[i]), 2);
  return se == 0.0 ? 99.0 : 10.0 * std::log10(255.0 * 255.0 * double(a.size()) / se);
}

/// What FFmpeg reads back from a video file.
struct Decoded {
  int width = 0, height = 0;
  std::string codec;
  AVPixelFormat pix_fmt = AV_PIX_FMT_NONE;
  AVColorSpace colorspace = AVCOL_SPC_UNSPECIFIED;
  AVColorRange range = AVCOL_RANGE_UNSPECIFIED;
  AVRational avg_rate{0, 1}, r_rate{0, 1}, time_base{0, 1};
  std::int64_t duration_us = 0;       // the file's, AV_TIME_BASE units
  std::vector<std::int64_t> pts;      // every decoded frame's, in time_base
  std::vector<std::int64_t> lengths;  // every frame's duration, in time_base
  std::vector<Image> frames;          // RGB24 of every frame
};

/// Colour back to RGB as a player does it: chroma interpolated bilinearly to every pixel.
constexpr int player_sws_flags = SWS_BILINEAR | SWS_ACCURATE_RND | SWS_FULL_CHR_H_INT;

/// `frame` (any pixel format) as RGB24, converted by the colour matrix and range it is tagged
/// with (BT.709 or else BT.601; limited or full range).
inline Image to_rgb(const AVFrame& frame) {
  SwsContext* sws = sws_getContext(
      frame.width, frame.height, static_cast<AVPixelFormat>(frame.format), frame.width,
      frame.height, AV_PIX_FMT_RGB24, player_sws_flags, nullptr, nullptr, nullptr);
  const int cs = frame.colorspace == AVCOL_SPC_BT709 ? SWS_CS_ITU709 : SWS_CS_DEFAULT;
  sws_setColorspaceDetails(sws, sws_getCoefficients(cs), frame.color_range == AVCOL_RANGE_JPEG,
                           sws_getCoefficients(SWS_CS_DEFAULT), 1, 0, 1 << 16, 1 << 16);
  Image rgb(std::size_t(frame.width) * frame.height * 3);
  std::uint8_t* dst[4] = {rgb.data()};
  const int dst_stride[4] = {frame.width * 3};
  sws_scale(sws, frame.data, frame.linesize, 0, frame.height, dst, dst_stride);
  sws_freeContext(sws);
  return rgb;
}

/// The stream's description as its container and codec parameters give it.
inline void describe(const AVFormatContext& fmt, const AVStream& st, Decoded& d) {
  d.width = st.codecpar->width, d.height = st.codecpar->height;
  d.codec = avcodec_get_name(st.codecpar->codec_id);
  d.pix_fmt = static_cast<AVPixelFormat>(st.codecpar->format);
  d.colorspace = st.codecpar->color_space, d.range = st.codecpar->color_range;
  d.avg_rate = st.avg_frame_rate, d.r_rate = st.r_frame_rate, d.time_base = st.time_base;
  d.duration_us = fmt.duration;
}

/// Decodes every frame of `file` (a single video stream) with libavformat + libavcodec, each
/// converted with to_rgb. An unreadable file gives an empty Decoded.
inline Decoded decode(const std::filesystem::path& file) {
  Decoded d;
  AVFormatContext* opened = nullptr;
  if (avformat_open_input(&opened, file.c_str(), nullptr, nullptr) < 0) return d;
  const std::unique_ptr<AVFormatContext, void (*)(AVFormatContext*)> fmt(
      opened, [](AVFormatContext* f) { avformat_close_input(&f); });
  EXPECT_GE(avformat_find_stream_info(fmt.get(), nullptr), 0);
  EXPECT_EQ(fmt->nb_streams, 1U);
  const AVStream& st = *fmt->streams[0];
  describe(*fmt, st, d);
  const AVCodec* codec = avcodec_find_decoder(st.codecpar->codec_id);
  const std::unique_ptr<AVCodecContext, void (*)(AVCodecContext*)> ctx(
      avcodec_alloc_context3(codec), [](AVCodecContext* c) { avcodec_free_context(&c); });
  avcodec_parameters_to_context(ctx.get(), st.codecpar);
  EXPECT_EQ(avcodec_open2(ctx.get(), codec, nullptr), 0);
  const std::unique_ptr<AVPacket, void (*)(AVPacket*)> pkt(av_packet_alloc(),
                                                           [](AVPacket* p) { av_packet_free(&p); });
  const std::unique_ptr<AVFrame, void (*)(AVFrame*)> frame(av_frame_alloc(),
                                                           [](AVFrame* f) { av_frame_free(&f); });
  auto receive = [&] {
    while (avcodec_receive_frame(ctx.get(), frame.get()) == 0) {
      d.pts.push_back(frame->best_effort_timestamp);
      d.lengths.push_back(frame->pkt_duration);
      d.frames.push_back(to_rgb(*frame));
    }
  };
  while (av_read_frame(fmt.get(), pkt.get()) == 0) {
    avcodec_send_packet(ctx.get(), pkt.get());
    av_packet_unref(pkt.get());
    receive();
  }
  avcodec_send_packet(ctx.get(), nullptr);  // drain the decoder's delayed frames
  receive();
  return d;
}

}  // namespace fixstep::testing
