// What a game's drawing costs a frame: a 1000-primitive overlay (app::Overlay / DrawList: lines,
// discs, circles, polygons, arrows, labels, spread over the frame in world and screen
// coordinates) over the 1000-body scene of bench_capture (bench/many_bodies.hpp), at 1280x720,
// against the same frames without it. Each measured frame is what a game's frame is: advance
// 1/60 s, record the overlay (the with_overlay case), draw. 30 frames a repetition after 60
// untimed ones, 15 repetitions interleaved at random, medians and minima reported; the last lines
// print
// the overlay's share of the frame, (with - without) / with, for frames drawn only and for frames
// captured as `fixstep render --out` captures them (PNG files written on a worker thread), and
// the target: <= 20 % of a captured frame ("at capture speed"), on the medians.
//   build/ci/bin/bench_overlay          (about two minutes)
#include <benchmark/benchmark.h>
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "../tests/support/overlay_shapes.hpp"
#include "../tests/support/scene_session.hpp"
#include "fixstep/app/session.hpp"
#include "fixstep/capture/capture.hpp"
#include "fixstep/core/loop.hpp"
#include "fixstep/render/draw_list.hpp"
#include "many_bodies.hpp"

namespace {

using namespace fixstep;

constexpr int width = 1280, height = 720;
constexpr int warm_frames = 60, clip_frames = 30;
constexpr int primitives = testing::overlay_shapes;

/// A clip's frames, drawn only (render) or also written as PNG files the way `fixstep render
/// --out` writes them (FrameWriter: the encoder on a worker thread, 2 frames in flight).
enum class Output { render, png };

std::filesystem::path out_dir() {
  auto dir =
      std::filesystem::temp_directory_path() / fmt::format("fixstep_bench_overlay_{}", ::getpid());
  std::filesystem::create_directories(dir);
  return dir;
}

void frame(benchmark::State& state, bool with_overlay, Output output, OverlayPath path) {
  Session session = testing::scene_session(bench::many_bodies(1000), width, height);
  session.set_overlay_path(path);
  const VirtualClock clock(60.0);
  DrawList list;
  double t = 0.0;
  auto one = [&] {
    session.advance(clock.frame_seconds());
    t += clock.frame_seconds();
    if (with_overlay) {
      testing::record_overlay(list, t);
      session.draw(list);
    } else {
      session.draw();
    }
  };
  for (int f = 0; f < warm_frames; ++f) one();
  for (auto _ : state) {
    if (output == Output::render) {
      for (int f = 0; f < clip_frames; ++f) one();
      continue;
    }
    FrameWriter writer(out_dir(), width, height);  // created and finished in the clip, as render
    for (int f = 0; f < clip_frames; ++f) {
      one();
      writer.submit(session.renderer().pixels());
    }
    writer.finish();
  }
}

/// Prints as the console reporter does and keeps every median's counters by benchmark name.
class MedianKeeper : public benchmark::ConsoleReporter {
 public:
  MedianKeeper() : ConsoleReporter(::isatty(STDOUT_FILENO) ? OO_Defaults : OO_Tabular) {}
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& r : runs) {
      if (r.run_type != Run::RT_Aggregate) continue;
      if (r.aggregate_name == "median") {
        medians[r.run_name.function_name] = r.GetAdjustedRealTime() / clip_frames;
        cpu_medians[r.run_name.function_name] = r.GetAdjustedCPUTime() / clip_frames;
      } else if (r.aggregate_name == "min") {
        mins[r.run_name.function_name] = r.GetAdjustedRealTime() / clip_frames;
        cpu_mins[r.run_name.function_name] = r.GetAdjustedCPUTime() / clip_frames;
      }
    }
  }
  std::map<std::string, double> medians;         ///< ms of wall time per frame
  std::map<std::string, double> cpu_medians;     ///< ms of CPU time per frame, every thread
  std::map<std::string, double> mins, cpu_mins;  ///< the same, the fastest repetition's
};

}  // namespace

int main(int argc, char** argv) {
  struct Case {
    bool with;
    OverlayPath path;
    const char* name;
  };
  // The overlay drawn by the CPU rasteriser (fixstep's default) and by GL (llvmpipe), beside.
  const Case cases[] = {{false, OverlayPath::cpu, "bodies_only"},
                        {true, OverlayPath::cpu, "with_overlay_1000"},
                        {true, OverlayPath::gl, "with_overlay_1000_gl"}};
  for (const auto& [output, name] : {std::pair{Output::render, "render"}, {Output::png, "png"}}) {
    for (const Case& c : cases) {
      benchmark::RegisterBenchmark(fmt::format("{}/{}", name, c.name).c_str(), frame, c.with,
                                   output, c.path)
          ->Unit(benchmark::kMillisecond)
          ->MeasureProcessCPUTime()  // llvmpipe rasterises on threads of its own
          ->UseRealTime()
          ->Iterations(1)  // one 60-frame clip per repetition
          ->Repetitions(15)
          ->ComputeStatistics(
              "min",
              [](const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); })
          ->ReportAggregatesOnly(true);
    }
  }
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
  // (with - without) / with of one output's medians (or fastest repetitions) in `m`, the overlay
  // drawn by `path` ("" the CPU rasteriser, "_gl" GL).
  auto report = [&](const char* output, const char* what, std::map<std::string, double>& m,
                    const char* path) {
    const double without = m[fmt::format("{}/bodies_only", output)];
    const double with = m[fmt::format("{}/with_overlay_1000{}", output, path)];
    if (!(without > 0.0 && with > 0.0)) return 1.0;
    const double share = (with - without) / with;
    std::printf("  %-6s %-3s %-40s %6.2f ms a frame, %6.2f ms with the overlay: %5.1f %%\n", output,
                *path ? "gl" : "cpu", what, without, with, 100.0 * share);
    return share;
  };
  std::printf(
      "\n1000 bodies at %dx%d without and with a %d-primitive overlay (its share of the "
      "frame), the overlay drawn by fixstep's CPU rasteriser (cpu) and by GL (gl):\n",
      width, height, primitives);
  for (const char* output : {"render", "png"}) {
    for (const char* path : {"", "_gl"}) {
      report(output, "wall time, medians", reporter.medians, path);
      report(output, "wall time, fastest repetitions", reporter.mins, path);
      report(output, "CPU time of every thread, medians", reporter.cpu_medians, path);
    }
  }
  // Judged on the medians, as every timing of docs/PERFORMANCE.md is: on a shared machine the
  // fastest of 15 repetitions of each case moves by several points from run to run.
  const double capture =
      report("png", "(target: <= 20 % of a captured frame)", reporter.medians, "");
  std::printf("  target <= 20 %% of a captured frame (PNG, wall time, medians): %s\n",
              capture <= 0.20 ? "met" : "MISSED");
  std::filesystem::remove_all(out_dir());
  return 0;
}
