// Video outputs that are not plain files (a FIFO, a directory) and the containers' limits at
// their edges: what video_limit_error accepts FFmpeg writes, what it refuses FFmpeg would not.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "fixstep/capture/video.hpp"
#include "fixstep/capture/video_limits.hpp"
#include "video_decode.hpp"

namespace fixstep {
namespace {

namespace fs = std::filesystem;
using testing::decode;
using testing::Decoded;

struct TempDir {
  fs::path path =
      fs::temp_directory_path() / ("fixstep_video_outputs_" + std::to_string(::getpid()));
  TempDir() {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() { fs::remove_all(path); }
};

/// A w x h RGBA8 frame whose colour changes with `frame`.
std::vector<std::uint8_t> frame_of(int w, int h, int frame) {
  std::vector<std::uint8_t> p(std::size_t(w) * h * 4, 255);
  for (std::size_t i = 0; i < p.size(); i += 4) {
    p[i] = static_cast<std::uint8_t>(40 * frame + i % 200);
    p[i + 1] = static_cast<std::uint8_t>(255 - 30 * frame);
  }
  return p;
}

/// Reads FIFO `fifo` into `copy` until its writer closes it, as `cat fifo > copy` does, but
/// opened without blocking and polled 100 ms at a time for at most 30 s: a hang guard only,
/// for a writer that never opens the FIFO (one that renames a file over it).
void drain_fifo(const fs::path& fifo, const fs::path& copy) {
  const int fd = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
  ASSERT_GE(fd, 0);
  std::ofstream out(copy, std::ios::binary);
  char buffer[65536];
  bool writer_seen = false;
  for (int polls = 0; polls < 300;) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, 100) == 0) {
      ++polls;
      continue;
    }
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n > 0) out.write(buffer, n), writer_seen = true;
    if (n == 0 && writer_seen) break;  // the writer closed it: the end
    if (n <= 0 && !writer_seen) ++polls, ::usleep(100000);
  }
  ::close(fd);
}

void write_frames(const fs::path& file, int w, int h, double fps, int n) {
  VideoWriter writer(file, w, h, fps);
  for (int f = 0; f < n; ++f) writer.submit(frame_of(w, h, f));
  writer.finish();
}

TEST(VideoOutputs, AnMp4IntoAFifoIsStreamedFragmentedAndDecodesWhole) {
  const TempDir dir;
  const fs::path fifo = dir.path / "clip.mp4", copy = dir.path / "copy.mp4";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::thread reader([&] { drain_fifo(fifo, copy); });
  write_frames(fifo, 64, 36, 30.0, 40);
  reader.join();
  EXPECT_TRUE(fs::is_fifo(fifo));
  const Decoded d = decode(copy);
  EXPECT_EQ(d.codec, "h264");
  EXPECT_EQ(d.width, 64);
  EXPECT_EQ(d.frames.size(), 40U);
  for (std::size_t k = 0; k < d.pts.size(); ++k) {  // frame k at k/30 s
    EXPECT_EQ(av_cmp_q(av_mul_q(AVRational{int(d.pts[k]), 1}, d.time_base), AVRational{int(k), 30}),
              0)
        << "frame " << k << " pts " << d.pts[k];
  }
}

TEST(VideoOutputs, ADirectoryIsRefusedBeforeAnythingIsWritten) {
  const TempDir dir;
  fs::create_directories(dir.path / "v.mp4");
  try {
    VideoWriter writer(dir.path / "v.mp4", 64, 36, 60.0);
    ADD_FAILURE() << "a directory was opened as a video";
  } catch (const CaptureError& e) {
    EXPECT_NE(std::string(e.what()).find("v.mp4: is a directory"), std::string::npos) << e.what();
  }
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path), fs::directory_iterator()), 1);
}

TEST(VideoOutputs, Mp4FrameDurationLimitIsTheMuxers) {
  // Rate 1/N: timescale 16384 (1 doubled to 10000 or more), a frame 16384 N ticks; the muxer
  // takes presentation offsets (up to 17 frames with B-frames) of at most 2^31 - 1 ticks:
  // N = 7710 is the longest frame, 7711 one too long. (With the default settings' 2
  // B-frames FFmpeg itself fails from N = 43691 on: "pts/dts pair unsupported".)
  EXPECT_EQ(mp4_timescale(VideoRate{1, 131071}), 16384);
  EXPECT_EQ(mp4_timescale(VideoRate{30, 1}), 15360);
  EXPECT_EQ(mp4_timescale(VideoRate{30000, 1001}), 30000);
  EXPECT_FALSE(video_limit_error(VideoFormat::mp4, 64, 36, 1.0 / 7710));
  const auto e = video_limit_error(VideoFormat::mp4, 64, 36, 1.0 / 7711);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->parameter, VideoParameter::fps);
  EXPECT_NE(e->text.find("too low for MP4"), std::string::npos) << e->text;
  EXPECT_NE(e->text.find("126337024 ticks"), std::string::npos) << e->text;
  const TempDir dir;  // what the check accepts, FFmpeg writes: 3 frames of 7710 s
  write_frames(dir.path / "slow.mp4", 64, 36, 1.0 / 7710, 3);
  const Decoded d = decode(dir.path / "slow.mp4");
  EXPECT_EQ(d.frames.size(), 3U);
  EXPECT_EQ(d.duration_us, std::int64_t(3) * 7710 * 1000000);
}

TEST(VideoOutputs, GifFrameDelayLimitIsSixteenBitsOfCentiseconds) {
  EXPECT_FALSE(video_limit_error(VideoFormat::gif, 64, 36, min_gif_fps));
  const auto e = video_limit_error(VideoFormat::gif, 64, 36, 0.001);
  ASSERT_TRUE(e);
  EXPECT_NE(e->text.find("too low for GIF"), std::string::npos) << e->text;
  EXPECT_TRUE(video_limit_error(VideoFormat::gif, 64, 36, min_gif_fps * 0.9999));
  const TempDir dir;  // at the limit every frame lasts 65535/100 s, none clamped
  write_frames(dir.path / "slow.gif", 16, 16, min_gif_fps, 3);
  const Decoded d = decode(dir.path / "slow.gif");
  ASSERT_EQ(d.frames.size(), 3U);
  EXPECT_EQ(d.pts, (std::vector<std::int64_t>{0, 65535, 131070}));
  EXPECT_EQ(d.lengths.back(), 65535);
}

TEST(VideoOutputs, SizeAndRateErrorsNameTheirParameter) {
  const auto odd = video_limit_error(VideoFormat::mp4, 321, 180, 60.0);
  ASSERT_TRUE(odd);
  EXPECT_EQ(odd->parameter, VideoParameter::size);
  EXPECT_EQ(odd->text.rfind("321x180 is odd", 0), 0U) << odd->text;
  EXPECT_FALSE(video_limit_error(VideoFormat::gif, 321, 180, 60.0));
  const auto fast = video_limit_error(VideoFormat::gif, 64, 36, 2e6);
  ASSERT_TRUE(fast);
  EXPECT_EQ(fast->parameter, VideoParameter::fps);
  EXPECT_NE(fast->text.find("above 1001000"), std::string::npos) << fast->text;
  EXPECT_FALSE(video_limit_error(VideoFormat::mp4, 64, 36, 1001000.0));
}

}  // namespace
}  // namespace fixstep
