// The world's kernel, WorldKernel<Real> (world_kernel.hpp), and its disc contacts,
// DiscContacts<Real> (disc_contacts.hpp), are class templates whose members are defined across
// the files below, one concept a file. They are compiled here as one translation unit, so that
// each class template is instantiated once, explicitly, for float and for double, instead of
// each file listing its own members (world_kernel.hpp declares the instantiations extern).
//
// The unit is the per-tick hot path, built at -O3 (engine/CMakeLists.txt): GCC vectorizes the
// sweeps' loops only there (at -O2 its "very cheap" cost model refuses loops that need a scalar
// remainder). -ffp-contract=off holds as everywhere, so no level changes a result.
#include "disc_candidates.cpp"     // discs: the candidate pairs
#include "disc_events.cpp"         // discs: motions, a pair's impact
#include "disc_fat.cpp"            // discs: candidate pairs recycled from fat boxes
#include "disc_gather.cpp"         // discs: the resting contacts gathered
#include "disc_halves.cpp"         // discs: a pile in two halves
#include "disc_holds.cpp"          // discs: impacts past the cap, and holds
#include "disc_lanes.cpp"          // discs: a tick's impacts in two lanes
#include "disc_live.cpp"           // discs: the ones a tick visits, with sleepers
#include "disc_queue.cpp"          // discs: the event queue of a tick's impacts
#include "disc_reach.cpp"          // discs: pairs of a path beyond its box
#include "disc_rest.cpp"           // discs: the resting solver
#include "disc_rows.cpp"           // discs: the solver's rows
#include "disc_segments.cpp"       // discs: resting on segments
#include "disc_sensors.cpp"        // discs: filters and sensors
#include "disc_walls.cpp"          // discs: walls within the impacts
#include "disc_windows.cpp"        // discs: a tick's impacts in windows
#include "world_contacts.cpp"      // planes
#include "world_coupled.cpp"       // links: the multi-pass integration
#include "world_discs.cpp"         // disc contacts, the world's side
#include "world_energy.cpp"        // the energy account and the state hash
#include "world_events.cpp"        // contact events
#include "world_implicit.cpp"      // links: implicit Euler's sparse solve
#include "world_input.cpp"         // a tick's input
#include "world_joint_checks.cpp"  // joints: their definitions checked
#include "world_joints.cpp"        // joints, the kernel's side
#include "world_kernel.cpp"        // construction, bodies and components, the force terms
#include "world_memory.cpp"        // what a snapshot holds
#include "world_movers.cpp"        // character movers, the kernel's side
#include "world_plane_blocks.cpp"  // planes: the first look, in blocks
#include "world_rolling.cpp"       // rolling discs' angles
#include "world_segments.cpp"      // segments and polylines
#include "world_sensors.cpp"       // sensors
#include "world_shape_sleep.cpp"   // bodies with shapes in the sleeping islands
#include "world_shapes.cpp"        // bodies with shapes, the kernel's side
#include "world_sleep.cpp"         // sleeping islands
#include "world_step.cpp"          // the fused sweep and the integrators
#include "world_tick.cpp"          // a tick's phases in order
#include "world_validation.cpp"    // values checked against their ranges

namespace fixstep::detail {

template class WorldKernel<float>;
template class WorldKernel<double>;
template class DiscContacts<float>;
template class DiscContacts<double>;

}  // namespace fixstep::detail
