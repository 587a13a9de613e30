// A scene loaded and its world built on a thread of its own, so that `fixstep view` keeps
// drawing while a large scene loads (10^6 bodies take several seconds here: generating them,
// the stability guard, building the world, measuring a state for rewind), shows how far the
// load is, and can drop it at once (quit, or a newer save).
//
// Nothing is shared while the load runs but its status (under a mutex) and its stop flag (an
// atomic): the loaded world passes to the caller whole, through a future, once the thread is
// done with it. The world is built exactly as on the calling thread (every step fixes its own
// floating-point mode: fixstep/core/float_mode.hpp), so its ticks are the same.
#pragma once

#include <atomic>
#include <cstdint>
#include <fixstep/core/world.hpp>
#include <fixstep/core/world_def.hpp>
#include <fixstep/scene/scene.hpp>
#include <functional>
#include <future>
#include <mutex>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "commands.hpp"
#include "view_rewind.hpp"

namespace fixstep::cli {

/// A scene ready to be shown: what BackgroundLoad makes.
struct LoadedWorld {
  Scene scene;                        ///< as load_with_overrides returned it
  std::vector<std::string> warnings;  ///< the scene's and the stability guard's, not yet printed
  WorldDef def;                       ///< scene.def, dissipation tracked (as Session wants)
  World sim;                          ///< World(def), at tick 0
  RewindPlan plan;                    ///< plan_rewind(sim)
};

/// What a load is doing now.
struct LoadStatus {
  std::string phase;  ///< "reading the scene", "generating the scene", "stability guard", ...
  std::string unit;   ///< the item the phase counts ("body", "iteration"), or "" for none
  std::uint64_t done = 0, total = 0;  ///< items, when unit is not ""
  double seconds = 0.0;               ///< s since the load started
};

/// One line for a LoadStatus: "stability guard: iteration 310/10000 (3 %), 4.2 s" or
/// "building the world, 6.1 s".
[[nodiscard]] std::string describe(const LoadStatus& status);

class BackgroundLoad {
 public:
  /// Starts loading `options`' scene (load_with_overrides, without a terminal progress line; its
  /// warnings kept in LoadedWorld), then building its world and planning its rewind
  /// (plan_rewind), on a thread of its own.
  /// `check`, when given, is called with the loaded scene before its world is built (view's
  /// memory estimate: a LimitError it throws is the load's error).
  explicit BackgroundLoad(SceneOptions options, std::function<void(const Scene&)> check = nullptr);
  /// cancel(), then waits for the thread (at most about a second: see cancel).
  ~BackgroundLoad();
  BackgroundLoad(const BackgroundLoad&) = delete;
  BackgroundLoad& operator=(const BackgroundLoad&) = delete;

  /// Whether the load has ended (take() returns at once).
  [[nodiscard]] bool ready() const;
  /// What the load is doing now.
  [[nodiscard]] LoadStatus status() const;
  /// Waits for the load's end and returns the world, or rethrows the load's error: SceneError,
  /// LimitError, std::invalid_argument (load_with_overrides, World(def)), std::bad_alloc,
  /// StopRequested after cancel(). Call once.
  [[nodiscard]] LoadedWorld take();
  /// Asks the load to stop at its next poll (a StopScope on its thread: no other thread's work
  /// is stopped): the generators poll every 65 536 items, the stability guard every iteration,
  /// the rewind plan's tick every substep; the longest stretch without a poll is building the
  /// world (World(def)): 0.65 s here for the largest legal one (10^6 bodies, 4·10^6 links),
  /// then freeing what was made takes a few tenths of a second more.
  void cancel() { stop_.store(1); }
  /// cancel(), then waits for the load's end: false when the load was stopped, true when it had
  /// ended before it saw the request (its world or error is dropped).
  [[nodiscard]] bool stop();

 private:
  void run(const SceneOptions& options, const std::function<void(const Scene&)>& check);
  void set_phase(std::string_view phase);
  void report(std::string_view what, std::string_view unit, std::uint64_t done,
              std::uint64_t total);

  std::chrono::steady_clock::time_point start_;
  mutable std::mutex mutex_;
  LoadStatus status_;  ///< under mutex_
  std::atomic<int> stop_{0};
  std::promise<LoadedWorld> promise_;
  std::future<LoadedWorld> result_;
  std::thread thread_;  ///< last: started once everything it uses exists
};

}  // namespace fixstep::cli
