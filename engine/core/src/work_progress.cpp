// The calling thread's progress callback (work_progress.hpp).
#include "fixstep/core/work_progress.hpp"

#include <utility>

namespace fixstep {

namespace {
thread_local const WorkProgress* current = nullptr;
}  // namespace

WorkProgressScope::WorkProgressScope(WorkProgress progress)
    : progress_(std::move(progress)), previous_(current) {
  current = &progress_;
}

WorkProgressScope::~WorkProgressScope() {
  current = previous_;
}

void report_work_progress(std::string_view what, std::string_view unit, std::uint64_t done,
                          std::uint64_t total) {
  if (current && *current) (*current)(what, unit, done, total);
}

}  // namespace fixstep
