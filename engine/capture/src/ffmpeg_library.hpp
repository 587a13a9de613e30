// FFmpeg's functions as capture calls them, loaded from its shared libraries the first time a
// video is written or checked (internal to fixstep::capture). A program that writes no video
// never loads FFmpeg: its five libraries and the ~140 they depend on would otherwise be mapped
// and relocated at every start of every program linking capture, before main(). The headers
// still give every type and signature; only the addresses come from dlopen/dlsym.
#pragma once

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavfilter/avfilter.h>
#include <libavfilter/buffersink.h>
#include <libavfilter/buffersrc.h>
#include <libavformat/avformat.h>
#include <libavutil/dict.h>
#include <libavutil/error.h>
#include <libavutil/frame.h>
#include <libavutil/imgutils.h>
#include <libavutil/log.h>
#include <libavutil/mathematics.h>
#include <libavutil/mem.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

namespace fixstep::av {

// X(library, function): every FFmpeg function capture calls, with the library that exports it
// (FFmpeg 5.1's split: avutil, avcodec, avformat, avfilter, swscale).
#define FIXSTEP_FFMPEG_FUNCTIONS(X)           \
  X(avutil, av_frame_alloc)                   \
  X(avutil, av_frame_free)                    \
  X(avutil, av_frame_get_buffer)              \
  X(avutil, av_frame_make_writable)           \
  X(avutil, av_frame_unref)                   \
  X(avutil, av_strerror)                      \
  X(avutil, av_strdup)                        \
  X(avutil, av_rescale)                       \
  X(avutil, av_rescale_q)                     \
  X(avutil, av_d2q)                           \
  X(avutil, av_div_q)                         \
  X(avutil, av_opt_set_int)                   \
  X(avutil, av_opt_set_bin)                   \
  X(avutil, av_log_get_level)                 \
  X(avutil, av_log_set_level)                 \
  X(avutil, av_image_copy_plane)              \
  X(avutil, av_dict_set)                      \
  X(avutil, av_dict_get)                      \
  X(avutil, av_dict_free)                     \
  X(avcodec, av_packet_alloc)                 \
  X(avcodec, av_packet_free)                  \
  X(avcodec, av_packet_rescale_ts)            \
  X(avcodec, avcodec_alloc_context3)          \
  X(avcodec, avcodec_find_encoder_by_name)    \
  X(avcodec, avcodec_free_context)            \
  X(avcodec, avcodec_open2)                   \
  X(avcodec, avcodec_parameters_from_context) \
  X(avcodec, avcodec_receive_packet)          \
  X(avcodec, avcodec_send_frame)              \
  X(avformat, avformat_alloc_output_context2) \
  X(avformat, avformat_free_context)          \
  X(avformat, avformat_new_stream)            \
  X(avformat, avformat_write_header)          \
  X(avformat, av_interleaved_write_frame)     \
  X(avformat, av_write_trailer)               \
  X(avformat, avio_closep)                    \
  X(avformat, avio_open)                      \
  X(avfilter, avfilter_get_by_name)           \
  X(avfilter, avfilter_graph_alloc)           \
  X(avfilter, avfilter_graph_config)          \
  X(avfilter, avfilter_graph_create_filter)   \
  X(avfilter, avfilter_graph_free)            \
  X(avfilter, avfilter_graph_parse_ptr)       \
  X(avfilter, avfilter_inout_alloc)           \
  X(avfilter, avfilter_inout_free)            \
  X(avfilter, av_buffersink_get_frame)        \
  X(avfilter, av_buffersink_get_time_base)    \
  X(avfilter, av_buffersrc_add_frame_flags)   \
  X(swscale, sws_freeContext)                 \
  X(swscale, sws_getCoefficients)             \
  X(swscale, sws_getContext)                  \
  X(swscale, sws_scale)                       \
  X(swscale, sws_setColorspaceDetails)

/// One pointer per function of FIXSTEP_FFMPEG_FUNCTIONS, with the header's exact type.
struct FfmpegFunctions {
// (`function` names a declaration here: it cannot be parenthesised.)
// NOLINTNEXTLINE(bugprone-macro-parentheses)
#define FIXSTEP_FFMPEG_MEMBER(library, function) decltype(&::function) function = nullptr;
  FIXSTEP_FFMPEG_FUNCTIONS(FIXSTEP_FFMPEG_MEMBER)
#undef FIXSTEP_FFMPEG_MEMBER
};

/// FFmpeg's functions, its libraries (libavutil.so.57, libavcodec.so.59, libavformat.so.59,
/// libavfilter.so.8, libswscale.so.6 for Debian 12's FFmpeg 5.1: the majors of the headers
/// built against) loaded on the first call, from any thread, once per process.
/// Throws CaptureError naming the library and dlopen's or dlsym's reason when one cannot be
/// loaded or lacks a function (every later call throws the same).
const FfmpegFunctions& ffmpeg();

}  // namespace fixstep::av
