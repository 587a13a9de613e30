// Progress of long work inside the engine that is not a loop of ticks a program drives itself:
// the load-time stability guard's power iteration on a large network (seconds for 10^6 bodies)
// and replay(), which steps a recording's ticks in one call.
// The engine reports; a program that wants to show it (the fixstep CLI's progress line)
// installs a callback for the thread doing the work. The engine depends on no program.
#pragma once

#include <cstdint>
#include <functional>
#include <string_view>

namespace fixstep {

/// `what` names the work ("stability guard", "replay"), `unit` its steps ("iteration",
/// "tick"); `done` of at most `total` steps are done.
using WorkProgress = std::function<void(std::string_view what, std::string_view unit,
                                        std::uint64_t done, std::uint64_t total)>;

/// Installs `progress` for the calling thread while it lives; scopes nest (the innermost
/// receives the reports, the one before is restored on destruction).
class WorkProgressScope {
 public:
  explicit WorkProgressScope(WorkProgress progress);
  ~WorkProgressScope();
  WorkProgressScope(const WorkProgressScope&) = delete;
  WorkProgressScope& operator=(const WorkProgressScope&) = delete;

 private:
  WorkProgress progress_;
  const WorkProgress* previous_;
};

/// Hands a report to the calling thread's innermost WorkProgressScope; nothing without one.
void report_work_progress(std::string_view what, std::string_view unit, std::uint64_t done,
                          std::uint64_t total);

}  // namespace fixstep
