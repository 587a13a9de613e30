#include "scene_load.hpp"

#include <fmt/format.h>

#include <chrono>
#include <exception>
#include <fixstep/core/stop_request.hpp>
#include <fixstep/core/work_progress.hpp>
#include <fixstep/core/world_def.hpp>
#include <fixstep/core/world_settings.hpp>
#include <utility>

namespace fixstep::cli {

std::string describe(const LoadStatus& s) {
  if (s.unit.empty() || s.total == 0) return fmt::format("{}, {:.1f} s", s.phase, s.seconds);
  return fmt::format("{}: {} {}/{} ({} %), {:.1f} s", s.phase, s.unit, s.done, s.total,
                     s.done * 100 / s.total, s.seconds);
}

BackgroundLoad::BackgroundLoad(SceneOptions options, std::function<void(const Scene&)> check)
    : start_(std::chrono::steady_clock::now()),
      status_{.phase = "reading the scene", .unit = {}},
      result_(promise_.get_future()),
      thread_([this, o = std::move(options), c = std::move(check)] { run(o, c); }) {}

BackgroundLoad::~BackgroundLoad() {
  cancel();
  thread_.join();
}

bool BackgroundLoad::ready() const {
  return result_.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
}

LoadStatus BackgroundLoad::status() const {
  const std::lock_guard lock(mutex_);
  LoadStatus s = status_;
  s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  return s;
}

LoadedWorld BackgroundLoad::take() {
  return result_.get();
}

bool BackgroundLoad::stop() {
  cancel();
  try {
    (void)result_.get();
  } catch (const StopRequested&) {
    return false;
  } catch (...) {  // an error of its own, before the request: dropped as a world would be
  }
  return true;
}

void BackgroundLoad::set_phase(std::string_view phase) {
  const std::lock_guard lock(mutex_);
  status_ = LoadStatus{.phase = std::string(phase), .unit = {}};
}

void BackgroundLoad::report(std::string_view what, std::string_view unit, std::uint64_t done,
                            std::uint64_t total) {
  const std::lock_guard lock(mutex_);
  status_ = LoadStatus{
      .phase = std::string(what), .unit = std::string(unit), .done = done, .total = total};
}

void BackgroundLoad::run(const SceneOptions& options,
                         const std::function<void(const Scene&)>& check) {
  const StopScope stop(stop_);
  const WorkProgressScope progress(
      [this](std::string_view what, std::string_view unit, std::uint64_t done,
             std::uint64_t total) { report(what, unit, done, total); });
  try {
    std::vector<std::string> warnings;
    Scene scene = load_with_overrides(options, &warnings);
    if (check) check(scene);  // before the world is built
    set_phase("building the world");
    scene.def.settings.track_dissipation = true;  // as Session's own build
    WorldDef def = scene.def;
    throw_if_stop_requested();
    World sim = build_world(scene, options.quiet, &warnings);
    set_phase("measuring a state for rewind");
    const RewindPlan plan = plan_rewind(sim);
    promise_.set_value(LoadedWorld{.scene = std::move(scene),
                                   .warnings = std::move(warnings),
                                   .def = std::move(def),
                                   .sim = std::move(sim),
                                   .plan = plan});
  } catch (...) {
    promise_.set_exception(std::current_exception());
  }
}

}  // namespace fixstep::cli
