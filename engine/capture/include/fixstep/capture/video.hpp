// Writing frames as one video file: MP4 (H.264, libx264) or animated GIF, through FFmpeg's
// libraries (libavcodec, libavformat, libswscale, libavfilter), atomically (or streamed into a
// pipe or device).
#pragma once

#include <cstdint>
#include <exception>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "fixstep/capture/capture.hpp"
#include "fixstep/capture/frame_pipeline.hpp"
#include "fixstep/io/output_target.hpp"

namespace fixstep {

/// The kinds of video file VideoWriter writes.
enum class VideoFormat {
  mp4,  ///< MPEG-4 file, H.264 video (libx264), yuv420p, BT.709 limited range, +faststart
  gif,  ///< animated GIF89a, a 256-colour palette per frame (libavfilter palettegen/paletteuse)
};

/// The container/codec a file name asks for: ".mp4" -> mp4 (H.264), ".gif" -> gif (the
/// extension compared case-insensitively); std::nullopt for any other extension or none.
[[nodiscard]] std::optional<VideoFormat> video_format_for(const std::filesystem::path& file);

/// H.264 quality: libx264's constant rate factor scale (0 = lossless, 51 = worst; each +6
/// roughly halves the bitrate). Ignored for GIF.
inline constexpr int min_video_crf = 0;
inline constexpr int max_video_crf = 51;

/// How MP4 files are encoded (GIF has no settings: see VideoWriter for what it does). The
/// defaults are the cheapest encoder settings for their quality, chosen by instruction count
/// (docs/perf/capture.md, "Encoder settings").
struct VideoSettings {
  /// libx264 constant rate factor, [min_video_crf, max_video_crf]: lower is better and larger.
  int crf = 18;
  /// libx264 preset: ultrafast, superfast, veryfast, faster, fast, medium, slow, slower,
  /// veryslow or placebo (slower: smaller files for the same crf, more CPU per frame).
  std::string preset = "ultrafast";
  /// libx264 tune: "" (none), film, animation, grain, stillimage, psnr, ssim, fastdecode or
  /// zerolatency. "animation" (flat areas, sharp edges) adds 2 B-frames to ultrafast's
  /// none: smaller files for less CPU.
  std::string tune = "animation";
  /// Encoder threads (libx264 "threads"), [0, 64]; 0 lets libx264 choose (about 1.5 per
  /// core). 1: the encoder already runs beside the drawing thread and llvmpipe's threads, and
  /// more threads cannot find an idle core.
  int threads = 1;
};

/// "" if `settings` are valid, else a message naming the field, its value and the valid range.
[[nodiscard]] std::string video_settings_error(const VideoSettings& settings);

/// The most frames per second a GIF keeps (frames/s): GIF frame delays are whole hundredths
/// of a second, and browsers (and FFmpeg's GIF demuxer) play delays under 2/100 s as
/// 10/100 s, so faster videos are thinned (see VideoWriter).
inline constexpr double max_gif_fps = 50.0;

/// Writes a sequence of RGBA8 frames as one video file, encoding on one worker thread while
/// the caller renders the next frame (the pipeline of FrameWriter, capture.hpp).
///
/// Timing: frame k (0-based, in submission order) has presentation time k / fps exactly: the
/// stream's time base is 1/fps as a rational (exact for integer fps, else av_d2q's closest
/// fraction with terms up to 1001000: 30000.0 / 1001 -> 30000/1001, 29.97 -> 2997/100), frame
/// k has pts k, and every frame lasts one tick. 120 frames at 60 fps are a 2.000 s video whose
/// stream reports a frame rate of 60 (avg_frame_rate and r_frame_rate).
///
/// MP4: each frame is converted from RGBA (sRGB, full range) to yuv420p (BT.709 matrix,
/// limited range, tagged so in the stream) with libswscale and encoded by libx264 at
/// `settings` (the defaults use B-frames: frames are stored out of order, presented in order).
/// The moov atom is moved to the front (+faststart) so browsers start playing before the
/// download ends. Streamed (below), the MP4 is fragmented instead (movflags frag_keyframe,
/// empty_moov, default_base_moof: an empty index first, then a fragment from each keyframe),
/// the form that needs no seeking back, and without B-frames (a fragment has no edit list to
/// shift their reordering delay away: frame k is still at k / fps); players and browsers play
/// it as they do the other.
///
/// GIF: each kept frame gets its own palette of 255 colours (libavfilter's palettegen,
/// stats_mode=single, plus one transparent entry) and each pixel its nearest palette colour
/// (paletteuse, no dithering: fixstep's flat colours and anti-aliased edges fit a frame's own
/// palette nearly exactly, so there is no 3-3-2 banding and no dither noise crawling between
/// frames); the GIF encoder stores only the rectangle that changed. GIF delays are whole
/// 1/100 s and browsers show delays of 0 or 1 as 10/100 s, so for fps > max_gif_fps only every
/// n-th frame is kept (n = ceil(fps / max_gif_fps): 60 fps -> every 2nd frame, 30 frames per
/// second of GIF); kept frame k keeps pts k, the GIF muxer rounds each frame's time to
/// 1/100 s, so delays alternate (60 fps: 3, 4, 3, 3, 4, 3 ... /100 s), and the last frame's
/// delay is set so the total is exact (120 frames at 60 fps: 60 GIF frames, 2.00 s). The GIF
/// loops forever.
///
/// Where the bytes go depends on what `file` names (classify_output, output_target.hpp), as
/// for AtomicFile. A regular file or a new name (a symbolic link: its final target): atomic,
/// the bytes go to a temporary file ".NAME.tmp.PID" beside it; only a successful finish()
/// renames it over the file (with the replaced file's permission bits). Errors, exceptions
/// and destruction without finish() remove it: nothing ever appears under `file` unless the
/// video is complete. A FIFO or a character device: streamed, written as encoded; an
/// abandoned video leaves what was written. A directory, block device or socket: refused.
/// Limits: video_limit_error (video_limits.hpp) is checked first.
///
/// Errors: the first frame the worker cannot encode or write stops the worker; the next
/// submit() or finish() rethrows its CaptureError (naming `file`).
///
/// FFmpeg's log: FFmpeg prints its encoders' settings and statistics to stderr at its default
/// level ("info"). If the application left that default, the first VideoWriter lowers it to
/// errors (av_log_set_level, process-wide); a level the application set is left alone.
///
/// Thread safety: call submit() and finish() from one thread (the producer).
class VideoWriter {
 public:
  /// Opens the encoder and the temporary file and starts the worker. `width` x `height` in
  /// pixels; `fps` frames per second of video; `in_flight` frame buffers (each width*height*4
  /// bytes) allocated here, so submit() allocates nothing.
  /// Throws std::invalid_argument naming `file` when: the extension is neither .mp4 nor .gif;
  /// the size or fps break the container's limits (video_limit_error: an odd size for MP4,
  /// a frame longer than MP4 or GIF can store, fps without a fraction); settings are invalid
  /// (video_settings_error); in_flight < 1.
  /// Throws CaptureError naming `file` when the file cannot be created (missing or unwritable
  /// directory), `file` is a directory, block device or socket, this FFmpeg lacks the encoder
  /// (libx264, gif) or a filter, or FFmpeg refuses the stream; nothing is left on disk then.
  VideoWriter(std::filesystem::path file, int width, int height, double fps,
              VideoSettings settings = {}, int in_flight = 3);
  /// Without a successful finish(): stops the worker (frames still queued are dropped),
  /// closes the encoder and removes the temporary file; nothing appears under file(). Never
  /// throws.
  ~VideoWriter();
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  /// Queues `rgba` (height rows of width*4 bytes, RGBA8, top row first, as
  /// Renderer::pixels(); alpha is ignored) as the next frame; it is copied before this
  /// returns. Blocks only while all in_flight buffers wait for the worker.
  /// Throws std::invalid_argument if the size does not match; CaptureError (naming file())
  /// if a frame failed in the worker, or after finish().
  void submit(std::span<const std::uint8_t> rgba);
  /// Encodes the frames still queued, flushes the encoder, writes the trailer, closes the
  /// temporary file and renames it onto file(). Throws CaptureError naming file() (then
  /// nothing is left on disk), also when no frame was submitted. Calling it again after
  /// success does nothing.
  void finish();

  /// Frames submitted so far (for GIF, including those thinned out).
  [[nodiscard]] std::uint64_t frames_submitted() const { return submitted_; }
  [[nodiscard]] const std::filesystem::path& file() const { return file_; }
  [[nodiscard]] VideoFormat format() const { return format_; }
  /// GIF: every frame_step()-th submitted frame is encoded (1 for MP4 and for fps <= 50).
  [[nodiscard]] int frame_step() const { return frame_step_; }

 private:
  class Encoder;
  void halt() noexcept;                           // stops the pipeline, dropping its error
  [[noreturn]] void rethrow_or_finished() const;  // after finish(): its error, or "finished"

  std::string open_destination();  // creates the temporary or opens the stream: FFmpeg's URL
  void publish();                  // renames the temporary over the target / closes the stream
  void discard() noexcept;         // removes the temporary / closes the stream

  std::filesystem::path file_;
  OutputTarget target_;        // what file_ names (classify_output)
  std::filesystem::path tmp_;  // file: ".NAME.tmp.PID" beside the target, renamed by finish()
  int stream_fd_ = -1;         // stream: the descriptor written through FFmpeg's pipe: URL
  VideoFormat format_;
  int width_, height_;
  int frame_step_ = 1;
  std::size_t frame_bytes_ = 0;
  std::unique_ptr<Encoder> encoder_;         // used by the pipeline's worker until it stops
  std::uint64_t submitted_ = 0;              // producer only
  bool finished_ = false;                    // producer only
  std::exception_ptr error_;                 // finish()'s failure, reported by later calls
  std::unique_ptr<FramePipeline> pipeline_;  // feeds encoder_; stopped before it is reset
};

}  // namespace fixstep
