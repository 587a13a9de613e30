// Video capture (VideoWriter): MP4 and GIF files read back with FFmpeg's own demuxers and
// decoders, compared with the pixels the PNG path writes; bad arguments and failures.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "fixstep/capture/video.hpp"
#include "fixstep/core/loop.hpp"
#include "fixstep/scene/scene.hpp"
#include "scene_session.hpp"
#include "video_decode.hpp"

namespace fixstep {
namespace {

using testing::decode;
using testing::Decoded;
using testing::Image;
using testing::psnr;
using testing::rgb_of_rgba;

std::filesystem::path temp_dir(const std::string& name) {
  auto d = std::filesystem::temp_directory_path() /
           ("fixstep_test_video_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

std::vector<std::string> names_in(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    names.push_back(e.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

std::string read_all(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

// --- 120 frames of default.toml at 640x360, 60 fps: MP4 and GIF written while rendering ----

constexpr int width = 640, height = 360, frames = 120;
constexpr double fps = 60.0;

struct Clip {
  std::filesystem::path dir, mp4, gif;
  std::vector<Image> rendered;  // RGB of every frame, as the PNG path stores them (lossless)
  Clip() = default;
  Clip(Clip&&) = default;
  Clip(const Clip&) = delete;
  Clip& operator=(const Clip&) = delete;
  ~Clip() {
    std::error_code ec;
    if (!dir.empty()) std::filesystem::remove_all(dir, ec);
  }
};

/// Renders default.toml as `fixstep render --size 640x360` does (tests/support/scene_session.hpp, a
/// 60 fps virtual clock) and submits every frame to an MP4 and a GIF VideoWriter.
const Clip& clip() {
  static const Clip c = [] {
    Clip c;
    c.dir = temp_dir("clip");
    c.mp4 = c.dir / "default.mp4", c.gif = c.dir / "default.gif";
    Session session = testing::scene_session(
        load_scene(FIXSTEP_SOURCE_DIR "/assets/scenes/default.toml"), width, height);
    const VirtualClock clock(fps);
    VideoWriter mp4(c.mp4, width, height, fps);
    VideoWriter gif(c.gif, width, height, fps);
    for (int f = 0; f < frames; ++f) {
      if (f > 0) session.advance(clock.frame_seconds());
      session.draw();
      mp4.submit(session.renderer().pixels());
      gif.submit(session.renderer().pixels());
      c.rendered.push_back(rgb_of_rgba(session.renderer().pixels()));
    }
    mp4.finish();
    gif.finish();
    return c;
  }();
  return c;
}

TEST(VideoClipMp4, HasEveryFrameAtTheExactRateAndSize) {
  const Decoded d = decode(clip().mp4);
  EXPECT_EQ(d.codec, "h264");
  EXPECT_EQ(d.pix_fmt, AV_PIX_FMT_YUV420P);
  EXPECT_EQ(d.colorspace, AVCOL_SPC_BT709);
  EXPECT_EQ(d.range, AVCOL_RANGE_MPEG);
  EXPECT_EQ(d.width, width);
  EXPECT_EQ(d.height, height);
  ASSERT_EQ(d.frames.size(), std::size_t(frames));
  EXPECT_EQ(av_cmp_q(d.avg_rate, AVRational{60, 1}), 0) << d.avg_rate.num << "/" << d.avg_rate.den;
  EXPECT_EQ(av_cmp_q(d.r_rate, AVRational{60, 1}), 0) << d.r_rate.num << "/" << d.r_rate.den;
  EXPECT_EQ(d.duration_us, 2'000'000);  // 120 frames / 60 fps, to the microsecond
  for (int k = 0; k < frames; ++k) {    // frame k at k/60 s exactly
    EXPECT_EQ(av_cmp_q(av_mul_q(AVRational{int(d.pts[k]), 1}, d.time_base), AVRational{k, 60}), 0)
        << "frame " << k << " pts " << d.pts[k];
  }
  EXPECT_EQ(names_in(clip().dir), (std::vector<std::string>{"default.gif", "default.mp4"}));
}

TEST(VideoClipMp4, FirstAndLastFramesMatchThePngPathsPixels) {
  // Measured with the default settings (ultrafast, tune animation, crf 18; SWS_POINT):
  // 45.3 dB (frame 0) and 44.4 dB (frame 119), decoded as a player does (chroma interpolated).
  // 4:2:0 colour alone caps these frames near 47 dB. A BT.601 / 709 mix-up stays above 35 dB
  // here (few saturated pixels): SaturatedColoursComeBackAsTheyWent catches that.
  const Decoded d = decode(clip().mp4);
  ASSERT_EQ(d.frames.size(), std::size_t(frames));
  for (int k : {0, frames - 1}) {
    const double db = psnr(clip().rendered[k], d.frames[k]);
    EXPECT_GE(db, 35.0) << "frame " << k;
    std::printf("MP4 frame %d: PSNR %.1f dB\n", k, db);
  }
}

TEST(VideoClipMp4, IndexComesFirstForStreaming) {
  const std::string bytes = read_all(clip().mp4);
  const auto moov = bytes.find("moov"), mdat = bytes.find("mdat");
  ASSERT_NE(moov, std::string::npos);
  ASSERT_NE(mdat, std::string::npos);
  EXPECT_LT(moov, mdat);  // +faststart
}

TEST(VideoClipGif, KeepsEveryOtherFrameOf60FpsWithDelaysBrowsersHonour) {
  const Decoded d = decode(clip().gif);
  EXPECT_EQ(d.codec, "gif");
  EXPECT_EQ(d.width, width);
  EXPECT_EQ(d.height, height);
  ASSERT_EQ(d.frames.size(), std::size_t(frames / 2));  // 60 fps -> 30 frames per second
  // The GIF demuxer's time base is 1/100 s; delays of 3 or 4 (never under 2, which browsers
  // and FFmpeg's demuxer would stretch to 10) add up to exactly 2 s.
  ASSERT_EQ(av_cmp_q(d.time_base, AVRational{1, 100}), 0);
  for (std::size_t j = 0; j < d.pts.size(); ++j) {
    EXPECT_EQ(d.pts[j], (200 * std::int64_t(j) + 30) / 60) << "GIF frame " << j;  // round(2j/60 s)
    EXPECT_GE(d.lengths[j], 3) << "GIF frame " << j;
    EXPECT_LE(d.lengths[j], 4) << "GIF frame " << j;
  }
  EXPECT_EQ(d.pts.back() + d.lengths.back(), 200);
}

TEST(VideoClipGif, FramesLookLikeThePngPaths) {
  // Measured: 69.0 dB (frame 0) and 65.8 dB (submitted frame 118, GIF frame 59): each frame's
  // own 255 colours cover default.toml's flat colours nearly exactly. Reusing the first frame's
  // palette (paletteuse without new=1) gives 48.3 dB on the last; a fixed 3-3-2 palette (each
  // channel truncated to 8, 8, 4 levels) about 22 dB.
  const Decoded d = decode(clip().gif);
  ASSERT_EQ(d.frames.size(), std::size_t(frames / 2));
  for (std::size_t j : {std::size_t{0}, d.frames.size() - 1}) {
    const double db = psnr(clip().rendered[2 * j], d.frames[j]);
    EXPECT_GE(db, 55.0) << "GIF frame " << j;
    std::printf("GIF frame %zu (submitted %zu): PSNR %.1f dB\n", j, 2 * j, db);
  }
}

// --- small synthetic clips: rates, arguments, failures -------------------------------------

/// A w x h RGBA8 test frame: a gradient with a bar at x = frame (so frames differ).
Image test_frame(int w, int h, int frame) {
  Image p(std::size_t(w) * h * 4);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      std::uint8_t* q = &p[(std::size_t(y) * w + x) * 4];
      const bool bar = (x - frame) % w == 0;
      q[0] = bar ? 255 : std::uint8_t(4 * x), q[1] = std::uint8_t(3 * y), q[2] = 90, q[3] = 255;
    }
  }
  return p;
}

void write_clip(const std::filesystem::path& file, int w, int h, double rate, int n) {
  VideoWriter writer(file, w, h, rate);
  for (int f = 0; f < n; ++f) writer.submit(test_frame(w, h, f));
  EXPECT_EQ(writer.frames_submitted(), std::uint64_t(n));
  writer.finish();
}

/// A w x h RGBA8 frame of vertical stripes, one per colour in `colours` (RGB).
Image stripes(int w, int h, const std::vector<std::array<std::uint8_t, 3>>& colours) {
  Image p(std::size_t(w) * h * 4);
  const int n = int(colours.size());
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const auto& c = colours[std::size_t(x * n / w)];
      std::copy(c.begin(), c.end(), &p[(std::size_t(y) * w + x) * 4]);
      p[(std::size_t(y) * w + x) * 4 + 3] = 255;
    }
  }
  return p;
}

TEST(VideoMp4, SaturatedColoursComeBackAsTheyWent) {
  // The colour matrix and range the pixels are converted with must be the ones the stream is
  // tagged with (BT.709, limited): a decoder converting back by the tags gets every colour of
  // the fixstep palette within 3 levels (the middle of each stripe, away from chroma edges).
  const std::vector<std::array<std::uint8_t, 3>> colours = {
      {230, 87, 46}, {255, 0, 0}, {0, 255, 0}, {0, 0, 255}, {46, 160, 230}, {250, 250, 250}};
  const auto dir = temp_dir("colours");
  const int w = 192, h = 32;
  {
    VideoWriter writer(dir / "c.mp4", w, h, 30.0, VideoSettings{.crf = 0});
    writer.submit(stripes(w, h, colours));
    writer.finish();
  }
  const Decoded d = decode(dir / "c.mp4");
  ASSERT_EQ(d.frames.size(), 1U);
  for (std::size_t i = 0; i < colours.size(); ++i) {
    const std::size_t x = (2 * i + 1) * w / (2 * colours.size()), y = h / 2;
    for (std::size_t ch = 0; ch < 3; ++ch) {
      EXPECT_NEAR(d.frames[0][(y * w + x) * 3 + ch], colours[i][ch], 3)
          << "colour " << i << " channel " << ch;
    }
  }
  std::filesystem::remove_all(dir);
}

TEST(VideoWriter, NonIntegerRateIsKeptAsAFraction) {
  const auto dir = temp_dir("ntsc");
  write_clip(dir / "ntsc.mp4", 64, 36, 30000.0 / 1001.0, 30);  // NTSC's "29.97"
  const Decoded d = decode(dir / "ntsc.mp4");
  EXPECT_EQ(d.frames.size(), 30U);
  EXPECT_EQ(av_cmp_q(d.avg_rate, AVRational{30000, 1001}), 0)
      << d.avg_rate.num << "/" << d.avg_rate.den;
  EXPECT_EQ(d.duration_us, 1'001'000);  // 30 frames of 1001/30000 s
  std::filesystem::remove_all(dir);
}

TEST(VideoWriter, GifAtOrBelow50FpsKeepsEveryFrame) {
  const auto dir = temp_dir("gif30");
  write_clip(dir / "a.GIF", 33, 17, 30.0, 9);  // upper-case extension, odd size: fine for GIF
  const Decoded d = decode(dir / "a.GIF");
  EXPECT_EQ(d.frames.size(), 9U);
  EXPECT_EQ(d.width, 33);
  EXPECT_EQ(d.height, 17);
  EXPECT_EQ(d.pts, (std::vector<std::int64_t>{0, 3, 7, 10, 13, 17, 20, 23, 27}));
  EXPECT_EQ(d.pts.back() + d.lengths.back(), 30);  // 9 frames / 30 fps = 0.30 s
  std::filesystem::remove_all(dir);
}

TEST(VideoWriter, FormatFollowsTheExtension) {
  EXPECT_EQ(video_format_for("a/b.mp4"), VideoFormat::mp4);
  EXPECT_EQ(video_format_for("B.Mp4"), VideoFormat::mp4);
  EXPECT_EQ(video_format_for("c.gif"), VideoFormat::gif);
  EXPECT_EQ(video_format_for("c.GIF"), VideoFormat::gif);
  EXPECT_EQ(video_format_for("d.avi"), std::nullopt);
  EXPECT_EQ(video_format_for("mp4"), std::nullopt);
  EXPECT_EQ(video_format_for("e.mp4.tmp"), std::nullopt);
}

/// The std::invalid_argument message of constructing a VideoWriter, or "".
template <class... Args>
std::string refusal(Args&&... args) {
  try {
    VideoWriter writer(std::forward<Args>(args)...);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(VideoWriter, RefusesBadArgumentsSayingWhy) {
  const auto dir = temp_dir("args");
  const auto mp4 = dir / "v.mp4";
  const std::string ext = refusal(dir / "v.avi", 64, 36, 60.0);
  EXPECT_NE(ext.find("v.avi"), std::string::npos) << ext;
  EXPECT_NE(ext.find(".mp4"), std::string::npos) << ext;
  EXPECT_NE(ext.find(".gif"), std::string::npos) << ext;
  const std::string odd = refusal(mp4, 641, 360, 60.0);
  EXPECT_NE(odd.find("641x360 is odd"), std::string::npos) << odd;
  EXPECT_NE(odd.find("even width and height"), std::string::npos) << odd;
  EXPECT_NE(refusal(mp4, 0, 36, 60.0).find("below 2x2"), std::string::npos);
  EXPECT_NE(refusal(dir / "v.gif", 0, 36, 60.0).find("outside 1x1"), std::string::npos);
  for (double bad : {0.0, -60.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    EXPECT_NE(refusal(mp4, 64, 36, bad).find("not a finite number > 0"), std::string::npos) << bad;
  }
  EXPECT_NE(refusal(mp4, 64, 36, 1e-9).find("too low for MP4"), std::string::npos);
  EXPECT_NE(refusal(mp4, 64, 36, 1e9).find("above 1001000"), std::string::npos);
  EXPECT_NE(refusal(mp4, 64, 36, 60.0, VideoSettings{.crf = 52}).find("crf 52"), std::string::npos);
  EXPECT_NE(refusal(mp4, 64, 36, 60.0, VideoSettings{.preset = "warp"}).find("\"warp\""),
            std::string::npos);
  EXPECT_NE(refusal(mp4, 64, 36, 60.0, VideoSettings{.tune = "fast"}).find("\"fast\""),
            std::string::npos);
  EXPECT_NE(refusal(mp4, 64, 36, 60.0, VideoSettings{.threads = -1}).find("threads -1"),
            std::string::npos);
  EXPECT_NE(refusal(mp4, 64, 36, 60.0, VideoSettings{}, 0).find("in_flight"), std::string::npos);
  EXPECT_TRUE(names_in(dir).empty());  // nothing was created
  std::filesystem::remove_all(dir);
}

TEST(VideoWriter, UnwritableDirectoryIsACaptureErrorNamingTheFile) {
  const auto dir = temp_dir("nodir");
  // Missing directory; a regular file as directory (both fail for root too).
  for (const auto& file : {dir / "missing" / "v.mp4", dir / "plain" / "v.gif"}) {
    std::ofstream(dir / "plain") << "x";
    try {
      VideoWriter writer(file, 64, 36, 60.0);
      ADD_FAILURE() << file << " was opened";
    } catch (const CaptureError& e) {
      EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(names_in(dir), std::vector<std::string>{"plain"});  // nothing left behind
  std::filesystem::remove_all(dir);
}

TEST(VideoWriter, WrongFrameSizeIsRefusedAndTheVideoGoesOn) {
  const auto dir = temp_dir("size");
  VideoWriter writer(dir / "v.mp4", 64, 36, 60.0);
  writer.submit(test_frame(64, 36, 0));
  EXPECT_THROW(writer.submit(test_frame(64, 34, 1)), std::invalid_argument);
  EXPECT_THROW(writer.submit({}), std::invalid_argument);
  writer.submit(test_frame(64, 36, 1));
  writer.finish();
  EXPECT_EQ(decode(dir / "v.mp4").frames.size(), 2U);
  EXPECT_NO_THROW(writer.finish());                                  // again: nothing to do
  EXPECT_THROW(writer.submit(test_frame(64, 36, 2)), CaptureError);  // finished
  std::filesystem::remove_all(dir);
}

TEST(VideoWriter, NoFramesIsAnErrorAndLeavesNothing) {
  const auto dir = temp_dir("empty");
  VideoWriter writer(dir / "v.gif", 64, 36, 60.0);
  try {
    writer.finish();
    ADD_FAILURE() << "finish() succeeded";
  } catch (const CaptureError& e) {
    EXPECT_NE(std::string(e.what()).find("no frames"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(names_in(dir).empty());
  std::filesystem::remove_all(dir);
}

TEST(VideoWriter, DestroyedWithoutFinishLeavesNothing) {
  const auto dir = temp_dir("abandon");
  for (const char* name : {"v.mp4", "v.gif"}) {
    VideoWriter writer(dir / name, 64, 36, 60.0);
    for (int f = 0; f < 10; ++f) writer.submit(test_frame(64, 36, f));
    EXPECT_EQ(names_in(dir).size(), 1U) << "the temporary file, while writing";
  }
  EXPECT_TRUE(names_in(dir).empty());
  std::filesystem::remove_all(dir);
}

/// In a child process: files may grow to 64 KiB at most (writes beyond fail with EFBIG, not
/// SIGXFSZ: VideoWriter ignores it, write_signals.hpp), and a noisy 256x144 MP4 outgrows that
/// within a few frames. Exits 0 when the worker's error reaches submit() or finish() as a
/// CaptureError naming the file and nothing is left behind.
[[noreturn]] void write_until_the_disk_is_full(const std::filesystem::path& dir) {
  std::signal(SIGXFSZ, SIG_DFL);  // the default, which kills: VideoWriter must change it
  const rlimit limit{64 * 1024, 64 * 1024};
  setrlimit(RLIMIT_FSIZE, &limit);
  std::string message;
  try {
    VideoWriter writer(dir / "v.mp4", 256, 144, 60.0, VideoSettings{.crf = 0}, 2);
    std::mt19937 rng(1);
    Image frame(256 * 144 * 4);
    for (int f = 0; f < 200; ++f) {
      for (auto& b : frame) b = static_cast<std::uint8_t>(rng());
      writer.submit(frame);
    }
    writer.finish();
  } catch (const CaptureError& e) {
    message = e.what();
  }
  const bool named = message.find((dir / "v.mp4").string()) != std::string::npos;
  std::fprintf(stderr, "message: %s\n", message.c_str());
  const bool nothing_left = names_in(dir).empty();
  std::filesystem::remove_all(dir);  // the threadsafe style made this directory in this child
  std::exit(named && nothing_left ? 0 : 1);
}

TEST(VideoWriter, WorkerErrorReachesTheCallerAndLeavesNothing) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  const auto dir = temp_dir("full");
  EXPECT_EXIT(write_until_the_disk_is_full(dir), ::testing::ExitedWithCode(0), "File too large");
  std::filesystem::remove_all(dir);
}

TEST(VideoWriter, FailedFinishLeavesNothingAndTheErrorSticks) {
  const auto dir = temp_dir("finish_fail");
  VideoWriter writer(dir / "v.mp4", 64, 36, 60.0);
  for (int f = 0; f < 5; ++f) writer.submit(test_frame(64, 36, f));
  // A directory made at v.mp4 after the writer opened (a directory there at the start is
  // refused then): renaming the finished video onto it fails.
  std::filesystem::create_directories(dir / "v.mp4" / "occupied");
  try {
    writer.finish();
    ADD_FAILURE() << "finish() succeeded";
  } catch (const CaptureError& e) {
    EXPECT_NE(std::string(e.what()).find((dir / "v.mp4").string()), std::string::npos) << e.what();
  }
  EXPECT_EQ(names_in(dir), std::vector<std::string>{"v.mp4"});  // only the blocking directory
  EXPECT_THROW(writer.finish(), CaptureError);
  EXPECT_THROW(writer.submit(test_frame(64, 36, 5)), CaptureError);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace fixstep
