// Headless capture throughput: how many 1280x720 frames per second `fixstep render` turns into
// PNG files or a video, against drawing alone and against stb_image_write's own deflate. Side
// by side in one run, on the same frames:
//   render_only  advance + draw, nothing encoded (the ceiling capture can reach)
//   naive_stb    + stb_image_write with its built-in deflate and its default filter choice
//                  (all five PNG filters tried per row), synchronous: fixstep before libdeflate
//   fast_sync    + PngEncoder (stb_image_write + libdeflate level 1, filter None), synchronous
//   shipped      + FrameWriter (the same encoder on a worker thread, 2 frames in flight):
//                  exactly what `fixstep render` does
//   mp4          + VideoWriter into clip.mp4 (H.264 at the default VideoSettings on a worker
//                  thread, 3 frames in flight): what `fixstep render --video x.mp4` does
//   gif          + VideoWriter into clip.gif (a palette per frame; 60 fps keeps every 2nd)
// Each measurement is a clip of 60 frames (one second at 60 fps) written as PNG files or one
// video file into a temporary directory, after 45 untimed frames so that every body's trail
// is full (the writer is created and finished inside the timed clip, as `render` does); five
// repetitions, interleaved at random with the other benchmarks', medians reported. Scenes:
// 1000 spring-damper and projectile bodies built in code (bench/many_bodies.hpp), and
// assets/scenes/default.toml (6 bodies). Then one frame of the 1000-body scene is encoded at
// every level, for the size/speed table. The last lines print the medians and the issues'
// targets: shipped >= 60 frames/s and shipped >= 2.5x naive_stb at 1000 bodies (PNG), and mp4
// >= 60 frames/s at 1000 bodies (video). KiB_per_frame is the output's size over the clip's
// 60 frames (for the GIF too, although it stores 30 of them).
//   build/ci/bin/bench_capture              (about 8 minutes on 2 cores)
//   build/ci/bin/bench_capture --benchmark_filter='mp4|gif'   (the video modes only)
//   build/ci/bin/bench_capture --benchmark_filter=encode    (the level table only)
#include <benchmark/benchmark.h>
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "../tests/support/scene_session.hpp"
#include "fixstep/app/session.hpp"
#include "fixstep/capture/capture.hpp"
#include "fixstep/capture/video.hpp"
#include "fixstep/core/loop.hpp"
#include "fixstep/scene/scene.hpp"
#include "many_bodies.hpp"

// The naive baseline: stb_image_write exactly as fixstep used it before libdeflate (built-in
// deflate at stb's default level 8, default filter choice). This copy is private to this file
// (STB_IMAGE_WRITE_STATIC) and its globals are left at stb's defaults.
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#define STBI_WRITE_NO_STDIO
#include <stb/stb_image_write.h>

namespace {

using namespace fixstep;

constexpr int width = 1280, height = 720;
constexpr int warm_frames = 45;  // Renderer::trail_frames: trails are full from here on
constexpr int clip_frames = 60;

Scene scene_named(const std::string& name) {
  if (name == "default") return load_scene(FIXSTEP_SOURCE_DIR "/assets/scenes/default.toml");
  return bench::many_bodies(1000);
}

/// The PNG of the naive baseline, as fixstep's write_png made it before libdeflate.
std::vector<std::uint8_t> naive_png(std::span<const std::uint8_t> rgba) {
  std::vector<std::uint8_t> png;
  png.reserve(rgba.size() / 4);
  auto append = [](void* context, void* data, int size) {
    auto* out = static_cast<std::vector<std::uint8_t>*>(context);
    const auto* p = static_cast<const std::uint8_t*>(data);
    out->insert(out->end(), p, p + size);
  };
  if (!stbi_write_png_to_func(append, &png, width, height, 4, rgba.data(), width * 4)) {
    throw CaptureError("naive stb_image_write encoding failed");
  }
  return png;
}

std::filesystem::path out_dir(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() /
             fmt::format("fixstep_bench_capture_{}", ::getpid()) / name;
  std::filesystem::create_directories(dir);
  return dir;
}

std::uintmax_t bytes_in(const std::filesystem::path& dir) {
  std::uintmax_t total = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) total += e.file_size();
  return total;
}

enum class Mode { render_only, naive_stb, fast_sync, shipped, mp4, gif };
constexpr const char* mode_names[] = {"render_only", "naive_stb", "fast_sync",
                                      "shipped",     "mp4",       "gif"};

void capture(benchmark::State& state, const std::string& scene_name, Mode mode) {
  Session session = testing::scene_session(scene_named(scene_name), width, height);
  const VirtualClock clock(60.0);
  for (int f = 0; f < warm_frames; ++f) {  // untimed: fill the trails
    if (f > 0) session.advance(clock.frame_seconds());
    session.draw();
  }
  const auto dir = out_dir(fmt::format("{}_{}", scene_name, static_cast<int>(mode)));
  PngEncoder encoder;
  const auto video = dir / (mode == Mode::gif ? "clip.gif" : "clip.mp4");
  for (auto _ : state) {
    std::optional<FrameWriter> writer;
    std::optional<VideoWriter> video_writer;
    if (mode == Mode::shipped) writer.emplace(dir, width, height);
    if (mode == Mode::mp4 || mode == Mode::gif) video_writer.emplace(video, width, height, 60.0);
    for (int f = 0; f < clip_frames; ++f) {
      session.advance(clock.frame_seconds());
      session.draw();
      const auto pixels = session.renderer().pixels();
      switch (mode) {
        case Mode::render_only:
          benchmark::DoNotOptimize(pixels.data());
          benchmark::ClobberMemory();
          break;
        case Mode::naive_stb:
          write_file_atomic(frame_path(dir, static_cast<std::uint64_t>(f)), naive_png(pixels));
          break;
        case Mode::fast_sync:
          encoder.write(frame_path(dir, static_cast<std::uint64_t>(f)), width, height, pixels);
          break;
        case Mode::shipped:
          writer->submit(pixels);
          break;
        case Mode::mp4:
        case Mode::gif:
          video_writer->submit(pixels);
          break;
      }
    }
    if (writer) writer->finish();              // timed: the clip is done when its last file is
    if (video_writer) video_writer->finish();  // timed: flush, trailer, rename
  }
  const double frames = double(state.iterations()) * clip_frames;
  state.counters["frames_per_s"] = benchmark::Counter(frames, benchmark::Counter::kIsRate);
  if (mode != Mode::render_only) {
    state.counters["KiB_per_frame"] = double(bytes_in(dir)) / clip_frames / 1024.0;
  }
  std::filesystem::remove_all(dir);
}

/// One frame of the 1000-body scene (frame 105: trails full), for the encoder table.
const std::vector<std::uint8_t>& sample_frame() {
  static const std::vector<std::uint8_t> frame = [] {
    Session session = testing::scene_session(bench::many_bodies(1000), width, height);
    const VirtualClock clock(60.0);
    for (int f = 0; f <= warm_frames + clip_frames; ++f) {
      if (f > 0) session.advance(clock.frame_seconds());
      session.draw();
    }
    const auto p = session.renderer().pixels();
    return std::vector<std::uint8_t>(p.begin(), p.end());
  }();
  return frame;
}

void encode(benchmark::State& state, int level) {  // level < 0: the naive stb baseline
  const auto& frame = sample_frame();
  std::size_t bytes = 0;
  if (level < 0) {
    for (auto _ : state) bytes = naive_png(frame).size();
  } else {
    PngEncoder encoder(PngSettings{.level = level});
    for (auto _ : state) bytes = encoder.encode(width, height, frame).size();
  }
  state.counters["KiB"] = double(bytes) / 1024.0;
}

/// The PNG lines of the summary (nothing when those modes did not run).
void print_png_summary(const std::string& scene, double render, double naive, double fast,
                       double shipped) {
  if (shipped <= 0.0 || naive <= 0.0) return;
  std::printf(
      "\n%s, %dx%d, medians in frames/s: render_only %.1f, naive_stb %.1f, fast_sync %.1f, "
      "shipped %.1f\n  shipped/naive_stb = %.2fx, shipped/render_only = %.0f%%\n",
      scene.c_str(), width, height, render, naive, fast, shipped, shipped / naive,
      render > 0 ? 100.0 * shipped / render : 0.0);
  if (scene == "many_bodies_1000") {
    std::printf("  target shipped >= 60 frames/s: %s (%.1f)\n", shipped >= 60.0 ? "met" : "MISSED",
                shipped);
    std::printf("  target shipped >= 2.5x naive_stb: %s (%.2fx)\n",
                shipped / naive >= 2.5 ? "met" : "MISSED", shipped / naive);
  }
}

/// The video lines of the summary (nothing when the video modes did not run).
void print_video_summary(const std::string& scene, double render, double mp4, double mp4_kib,
                         double gif, double gif_kib) {
  if (mp4 <= 0.0 && gif <= 0.0) return;
  std::printf(
      "\n%s, %dx%d video, medians: mp4 %.1f frames/s (%.0f%% of render_only), %.1f KiB/frame; "
      "gif %.1f frames/s, %.1f KiB/frame\n",
      scene.c_str(), width, height, mp4, render > 0 ? 100.0 * mp4 / render : 0.0, mp4_kib, gif,
      gif_kib);
  if (scene == "many_bodies_1000" && mp4 > 0.0) {
    std::printf("  target mp4 >= 60 frames/s: %s (%.1f)\n", mp4 >= 60.0 ? "met" : "MISSED", mp4);
  }
}

/// Prints as the console reporter does and keeps every median's counters by benchmark name.
class MedianKeeper : public benchmark::ConsoleReporter {
 public:
  MedianKeeper() : ConsoleReporter(::isatty(STDOUT_FILENO) ? OO_Defaults : OO_Tabular) {}
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& r : runs) {
      if (r.run_type == Run::RT_Aggregate && r.aggregate_name == "median") {
        for (const auto& [key, counter] : r.counters) {
          medians[r.run_name.function_name][key] = counter.value;
        }
      }
    }
  }
  std::map<std::string, std::map<std::string, double>> medians;
};

}  // namespace

int main(int argc, char** argv) {
  for (const std::string scene : {"many_bodies_1000", "default"}) {
    for (int m = 0; m < int(std::size(mode_names)); ++m) {
      benchmark::RegisterBenchmark(fmt::format("capture/{}/{}", scene, mode_names[m]).c_str(),
                                   capture, scene, static_cast<Mode>(m))
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime()  // the encoding of `shipped` runs on another thread
          ->Iterations(1)  // one 60-frame clip per repetition
          ->Repetitions(5)
          ->ReportAggregatesOnly(true);
    }
  }
  benchmark::RegisterBenchmark("encode/naive_stb", encode, -1)
      ->Unit(benchmark::kMillisecond)
      ->Repetitions(3)
      ->ReportAggregatesOnly(true);
  for (int level : {0, 1, 2, 3, 6, 9, 12}) {
    benchmark::RegisterBenchmark(fmt::format("encode/level:{}", level).c_str(), encode, level)
        ->Unit(benchmark::kMillisecond)
        ->Repetitions(3)
        ->ReportAggregatesOnly(true);
  }
  // Interleave the repetitions of all benchmarks in random order (unless told otherwise), so
  // that load from other processes on a shared machine falls on every mode alike and the
  // ratios stay comparable.
  std::vector<char*> args(argv, argv + argc);
  std::string interleave = "--benchmark_enable_random_interleaving=true";
  if (std::none_of(args.begin(), args.end(), [](const char* a) {
        return std::string_view(a).starts_with("--benchmark_enable_random_interleaving");
      })) {
    args.push_back(interleave.data());
  }
  argc = static_cast<int>(args.size());
  args.push_back(nullptr);
  argv = args.data();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  MedianKeeper reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();

  // The issues' targets, from the medians of this run.
  for (const std::string scene : {"many_bodies_1000", "default"}) {
    auto median = [&](const char* mode, const char* counter) {
      const auto it = reporter.medians.find(fmt::format("capture/{}/{}", scene, mode));
      return it == reporter.medians.end() ? 0.0 : it->second[counter];
    };
    auto fps = [&](const char* mode) { return median(mode, "frames_per_s"); };
    print_png_summary(scene, fps("render_only"), fps("naive_stb"), fps("fast_sync"),
                      fps("shipped"));
    print_video_summary(scene, fps("render_only"), fps("mp4"), median("mp4", "KiB_per_frame"),
                        fps("gif"), median("gif", "KiB_per_frame"));
  }
  std::filesystem::remove_all(std::filesystem::temp_directory_path() /
                              fmt::format("fixstep_bench_capture_{}", ::getpid()));
  return 0;
}
