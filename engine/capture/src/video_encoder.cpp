#include "video_encoder.hpp"

#include <mutex>
#include <string>

namespace fixstep {

namespace {

// Builds an AVDictionary from key/value pairs; what avcodec_open2 / avformat_write_header
// leave in it are options nobody took (a typo or an option this FFmpeg lacks).
class Dict {
 public:
  void set(const char* key, const std::string& value) {
    av::ffmpeg().av_dict_set(&d_, key, value.c_str(), 0);
  }
  AVDictionary** get() { return &d_; }
  [[nodiscard]] const char* first_key() const {
    const AVDictionaryEntry* e = av::ffmpeg().av_dict_get(d_, "", nullptr, AV_DICT_IGNORE_SUFFIX);
    return e ? e->key : nullptr;
  }
  ~Dict() {
    if (d_) av::ffmpeg().av_dict_free(&d_);  // (an empty one never needed FFmpeg loaded)
  }
  Dict() = default;
  Dict(const Dict&) = delete;
  Dict& operator=(const Dict&) = delete;

 private:
  AVDictionary* d_ = nullptr;
};

const AVCodec* find_encoder(VideoFormat format, const std::filesystem::path& file) {
  const char* name = format == VideoFormat::mp4 ? "libx264" : "gif";
  const AVCodec* codec = av::ffmpeg().avcodec_find_encoder_by_name(name);
  if (!codec) {
    throw CaptureError(fmt::format(
        "cannot write {}: this FFmpeg has no \"{}\" encoder (Debian 12's libavcodec59 has it)",
        file.string(), name));
  }
  return codec;
}

// FFmpeg logs at "info" by default: x264's settings and statistics, palettegen's colour
// counts, on every video. If the application left FFmpeg's level at that default, lower it
// to errors (the errors also reach the caller as CaptureErrors).
void quiet_ffmpeg_once() {
  static std::once_flag once;
  std::call_once(once, [] {
    if (av::ffmpeg().av_log_get_level() == AV_LOG_INFO) av::ffmpeg().av_log_set_level(AV_LOG_ERROR);
  });
}

}  // namespace

VideoWriter::Encoder::Encoder(const std::string& url, const std::filesystem::path& file,
                              const Options& options)
    : file_(file), step_(options.step) {
  quiet_ffmpeg_once();
  const char* muxer = options.format == VideoFormat::mp4 ? "mp4" : "gif";
  // The muxer is named: the temporary file's name does not end in .mp4 / .gif.
  AVFormatContext* mux = nullptr;
  av::check(av::ffmpeg().avformat_alloc_output_context2(&mux, nullptr, muxer, url.c_str()), file_,
            fmt::format("cannot set up the {} muxer", muxer));
  mux_.reset(mux);
  packet_.reset(av::ffmpeg().av_packet_alloc());
  if (!packet_) throw CaptureError(fmt::format("cannot write {}: out of memory", file_.string()));
  const AVRational time_base{options.rate.den, options.rate.num};
  if (options.format == VideoFormat::mp4) {
    yuv_.emplace(options.width, options.height, file_);
  } else {
    palette_.emplace(options.width, options.height, time_base, file_);
    paletted_.reset(av::ffmpeg().av_frame_alloc());
    if (!paletted_) {
      throw CaptureError(fmt::format("cannot write {}: out of memory", file_.string()));
    }
  }
  open_codec(options);
  open_file(url, options);
}

VideoWriter::Encoder::~Encoder() {
  // FFmpeg 5.1's GIF muxer holds the last packet back (its delay depends on the next one) and
  // frees it only in its trailer, so an abandoned GIF would leak it: write the trailer into
  // the temporary file, which the caller removes. (The MP4 muxer frees all in its deinit.)
  if (palette_ && header_written_ && !trailer_written_) av::ffmpeg().av_write_trailer(mux_.get());
}

void VideoWriter::Encoder::open_codec(const Options& options) {
  const AVCodec* codec = find_encoder(options.format, file_);
  stream_ = av::ffmpeg().avformat_new_stream(mux_.get(), nullptr);
  codec_.reset(av::ffmpeg().avcodec_alloc_context3(codec));
  if (!stream_ || !codec_) {
    throw CaptureError(fmt::format("cannot write {}: out of memory", file_.string()));
  }
  AVCodecContext& c = *codec_;
  c.width = options.width;
  c.height = options.height;
  c.time_base = AVRational{options.rate.den, options.rate.num};
  c.framerate = av::ffmpeg().av_div_q(options.rate, AVRational{options.step, 1});
  c.sample_aspect_ratio = AVRational{1, 1};
  Dict opts;
  if (options.format == VideoFormat::mp4) {
    c.pix_fmt = AV_PIX_FMT_YUV420P;
    av::tag_bt709_limited(c);
    c.thread_count = options.settings.threads;
    opts.set("preset", options.settings.preset);
    opts.set("crf", std::to_string(options.settings.crf));
    if (!options.settings.tune.empty()) opts.set("tune", options.settings.tune);
    // A stream's fragments carry no edit list that players apply: with B-frames its first
    // frame would be shown two frames late. In decode order, pts = dts and frame k is at k.
    if (options.streamed) c.max_b_frames = 0;
  } else {
    c.pix_fmt = AV_PIX_FMT_PAL8;
  }
  if (mux_->oformat->flags & AVFMT_GLOBALHEADER) c.flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  av::check(av::ffmpeg().avcodec_open2(&c, codec, opts.get()), file_,
            fmt::format("the {} encoder refuses the stream", codec->name));
  if (const char* unused = opts.first_key()) {
    throw CaptureError(fmt::format("cannot write {}: the {} encoder has no option \"{}\"",
                                   file_.string(), codec->name, unused));
  }
  av::check(av::ffmpeg().avcodec_parameters_from_context(stream_->codecpar, &c), file_,
            "cannot describe the stream");
  stream_->time_base = c.time_base;
  stream_->avg_frame_rate = c.framerate;
}

void VideoWriter::Encoder::open_file(const std::string& url, const Options& options) {
  av::check(av::ffmpeg().avio_open(&mux_->pb, url.c_str(), AVIO_FLAG_WRITE), file_,
            "cannot create the file");
  Dict opts;
  // faststart: after the last frame the muxer rewrites the file with the index (moov) first,
  // so a browser plays the video while it downloads. A stream cannot be rewritten: fragments
  // (an empty index first, then a fragment per keyframe) play the same way.
  if (options.format == VideoFormat::mp4) {
    opts.set("movflags",
             options.streamed ? "+frag_keyframe+empty_moov+default_base_moof" : "+faststart");
  }
  av::check(av::ffmpeg().avformat_write_header(mux_.get(), opts.get()), file_,
            "cannot write the header");
  header_written_ = true;
}

void VideoWriter::Encoder::encode(std::span<const std::uint8_t> rgba, std::int64_t pts) {
  if (yuv_) {
    send(yuv_->convert(rgba, pts));
  } else {
    palette_->push(rgba, pts);
    drain_palette();
  }
}

void VideoWriter::Encoder::drain_palette() {
  while (palette_->pull(paletted_.get())) {
    send(paletted_.get());
    av::ffmpeg().av_frame_unref(paletted_.get());
  }
}

void VideoWriter::Encoder::send(const AVFrame* frame) {
  if (frame) last_pts_ = frame->pts;
  av::check(av::ffmpeg().avcodec_send_frame(codec_.get(), frame), file_,
            "the encoder refused a frame");
  write_packets();
}

void VideoWriter::Encoder::write_packets() {
  for (;;) {
    const int err = av::ffmpeg().avcodec_receive_packet(codec_.get(), packet_.get());
    if (err == AVERROR(EAGAIN) || err == AVERROR_EOF) return;
    av::check(err, file_, "the encoder failed");
    // Every frame lasts `step` ticks of the time base: the last frame too, so a clip of N
    // frames lasts exactly N * step / rate seconds.
    packet_->duration = step_;
    packet_->stream_index = stream_->index;
    av::ffmpeg().av_packet_rescale_ts(packet_.get(), codec_->time_base, stream_->time_base);
    // av_interleaved_write_frame takes the packet's data and leaves it blank.
    av::check(av::ffmpeg().av_interleaved_write_frame(mux_.get(), packet_.get()), file_,
              "cannot write a frame");
    // A failed write (a full disk, EFBIG past `ulimit -f`, a closed pipe) is kept in the
    // I/O context and may not be returned until the trailer: stop at the first one.
    if (mux_->pb && mux_->pb->error < 0) av::fail(file_, "cannot write a frame", mux_->pb->error);
  }
}

void VideoWriter::Encoder::finish() {
  if (palette_) {
    palette_->end();
    drain_palette();
  }
  if (last_pts_ < 0) {
    throw CaptureError(fmt::format("cannot write {}: no frames were submitted", file_.string()));
  }
  send(nullptr);
  if (palette_) set_gif_final_delay();
  trailer_written_ = true;  // even if it fails: av_write_trailer is not to be called twice
  av::check(av::ffmpeg().av_write_trailer(mux_.get()), file_, "cannot finish the file");
  av::check(av::ffmpeg().avio_closep(&mux_->pb), file_, "cannot close the file");
}

void VideoWriter::Encoder::set_gif_final_delay() {
  // The GIF muxer gives each frame the time to the next one's pts (in its 1/100 s time base)
  // and the last frame, unless told, the delay before it: the total would be off by the
  // rounding. The last frame ends at (last pts + step) / rate: its delay is what remains.
  const AVRational tb = codec_->time_base;
  const std::int64_t last = av::ffmpeg().av_rescale_q(last_pts_, tb, stream_->time_base);
  const std::int64_t end = av::ffmpeg().av_rescale_q(last_pts_ + step_, tb, stream_->time_base);
  av::check(av::ffmpeg().av_opt_set_int(mux_->priv_data, "final_delay", end - last, 0), file_,
            "the GIF muxer has no final_delay option");
}

}  // namespace fixstep
