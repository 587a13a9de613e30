// One tick of the world (WorldKernel::step): its phases in order, each named for what it does
// and defined in the file named beside it. docs/ARCHITECTURE.md lists the same phases.
#include <algorithm>
#include <cstdint>

#include "disc_contacts.hpp"
#include "fixstep/core/float_mode.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/step_results.hpp"
#include "phase_clock.hpp"
#include "second_thread.hpp"
#include "shape_world.hpp"
#include "world_kernel.hpp"

namespace fixstep {

template <class Real>
typename detail::WorldKernel<Real>::TickPlan detail::WorldKernel<Real>::plan_tick() {
  TickPlan plan;
  // Contacts with planes only when the world has planes and colliders; static and kinematic
  // bodies and disc-disc contacts only when declared: one branch each per tick otherwise.
  plan.planes = contact_.active;
  plan.immovable = !immovable_.body.empty();
  // With sleeping islands, a tick in which every disc sleeps skips the disc phases (and no body
  // with shapes moves: their events are made with the discs').
  const bool active = discs_ && discs_->active();
  plan.shapes_still = shape_world_ && sleep_ && sleepers_ != 0 && shapes_at_rest();
  plan.quiet =
      sleep_ && sleepers_ != 0 && active && discs_at_rest() && (!shape_world_ || plan.shapes_still);
  plan.discs = active && !plan.quiet;
  // The integration has a worker of its own with links or the dissipation account
  // (step_multipass); the discs' second thread then wakes after it, else during it.
  plan.own_worker = !net_.a.empty() || settings_.track_dissipation;
  if (plan.discs) choose_disc_threads();  // world_discs.cpp
  return plan;
}

template <class Real>
std::uint64_t detail::WorldKernel<Real>::handed_passes() const {
  return (discs_ ? discs_->handed_passes() : 0) +
         (shape_world_ ? shape_world_->handed_passes() : 0);
}

template <class Real>
void detail::WorldKernel<Real>::step(const TickInput& input) {
  const IeeeFloatMode ieee;           // no state depends on the caller's FPU mode (float_mode.hpp)
  if (terms_dirty_) rebuild_terms();  // world_kernel.cpp
  if (!joints_broken_.empty()) joints_broken_.clear();
  apply_input(input);                             // world_input.cpp
  if (!movers_.data.empty()) move_movers();       // world_movers.cpp: against the tick's start
  if (keep_previous_) keep_previous_positions();  // world_step.cpp
  const TickPlan plan = plan_tick();
  // threads_used(): 2 if a pass of the disc or shape phases is handed to a second thread.
  const bool shared = discs_ || shape_world_;
  const std::uint64_t handed = shared ? handed_passes() : 0;
  // The shape contacts' start (world_shapes.cpp), unless this tick runs no shape phase: then
  // no body with shapes moves, and the next tick that runs one saves its own.
  const bool shapes_run = shape_world_ && (plan.discs || !(plan.quiet || plan.shapes_still));
  if (shapes_run) save_shape_start();
  // Two threads: the discs' second thread spins between the disc phases' passes to the end of
  // the contact events (second_thread.hpp).
  auto disc_thread = [&] { return plan.discs ? discs_->second_thread(disc_count_) : nullptr; };
  detail::SecondThreadRun early(plan.own_worker ? nullptr : disc_thread());
  detail::PhaseClock clock(plan.discs);  // World::profile(): read only with disc contacts
  integrate_with_input(input, plan.immovable, plan.discs);  // world_input.cpp, world_step.cpp
  if (!movers_.data.empty()) place_movers();                // where their slides left them, exactly
  profile_.integrate = clock.lap();
  detail::SecondThreadRun run(disc_thread());  // nothing if `early` holds it open
  const std::size_t plane_capped = plan.planes ? resolve_contacts() : 0;  // world_contacts.cpp
  if (plan.discs) {
    resolve_discs();                     // broadphase, impacts, resting solver: world_discs.cpp
    if (shape_world_) resolve_shapes();  // world_shapes.cpp
    update_contact_events(true);         // world_events.cpp
    update_sensor_events(true);          // world_sensors.cpp
    // The events: what the contacts' phases (broadphase, impacts, resting) leave of the lap.
    const StepProfile& p = profile_;
    profile_.events = std::max(clock.lap() - p.broadphase - p.impacts - p.resting, 0.0);
    profile_.step = clock.total();
    run.close(), early.close();  // the worker sleeps through the rest of the tick
  } else if (plan.quiet || plan.shapes_still) {
    quiet_discs();  // world_sleep.cpp: nothing moves, so no contact phase runs
  } else if (shape_world_) {
    resolve_shapes();
    if (profile_.step != 0.0) profile_ = StepProfile{};
    update_contact_events(false);
    update_sensor_events(false);
  } else {
    end_disc_events();  // world_events.cpp
  }
  if (!movers_.data.empty()) finish_movers();   // their slid velocities
  if (rolling_) integrate_angles();             // world_rolling.cpp
  if (segments_.moves()) place_segments();      // where the tick left the carriers
  if (sleep_) finish_sleep(input, plan.discs);  // world_sleep.cpp
  if (plan.planes) contact_stats_.capped = (plan.discs ? contact_stats_.capped : 0) + plane_capped;
  contact_stats_.free_stepped = stepped_;
  contact_stats_.plane_tested = plan.planes ? plane_visited_ : 0;
  contact_stats_.shape_visited = shapes_run ? shape_world_->visited() : 0;
  contact_stats_.joint_visited = shapes_run ? shape_world_->joints_visited() : 0;
  awake_.primed = awake_.on;  // a whole tick has passed over the sleepers (awake_runs.hpp)
  if (shared && handed_passes() != handed) threads_used_ = 2;

  flush_state_subnormals();  // world_step.cpp
  check_energy_account();    // world_step.cpp: the guard's view of the dissipated energy
}

}  // namespace fixstep
