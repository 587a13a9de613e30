#include "view_rewind.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fixstep/core/stop_request.hpp>
#include <fixstep/core/world_settings.hpp>

namespace fixstep::cli {

RewindPlan plan_rewind(const World& sim) {
  const double dt = sim.settings().dt;
  throw_if_stop_requested();  // before and after the copy: half a second for 10^6 bodies
  World probe = sim;
  throw_if_stop_requested();
  probe.step();
  const std::size_t bytes = std::max(sim.snapshot_bytes(), probe.snapshot_bytes());
  return {.capacity = rewind_capacity(rewind_seconds, dt, bytes, rewind_max_bytes),
          .state_bytes = bytes,
          .dt = dt};
}

RewindBuffer make_rewind(const RewindPlan& plan) {
  if (static_cast<double>(plan.capacity) < std::ceil(rewind_seconds / plan.dt)) {
    std::fprintf(stderr,
                 "note: rewind keeps the last %.3g s (%zu ticks), not %g s: a state of this world "
                 "takes %.1f MiB and rewind at most %zu MiB\n",
                 static_cast<double>(plan.capacity) * plan.dt, plan.capacity, rewind_seconds,
                 static_cast<double>(plan.state_bytes) / (1 << 20), rewind_max_bytes >> 20);
  }
  return RewindBuffer(plan.capacity);
}

}  // namespace fixstep::cli
