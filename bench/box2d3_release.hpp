// The functions of one Box2D v3 release's steppers (discs_box2d3.cpp, boxes_box2d3.cpp,
// joints_box2d3.cpp), in a namespace per release: the sources are compiled once per release
// (bench/box2d3.cmake, with FIXSTEP_BOX2D3_MINOR 1 or 2) and define the functions of
// FIXSTEP_BOX2D3_NS; box2d3_peers.cpp (and joints_report.cpp for make_joints) calls the releases
// that were built. Internal to bench/.
#pragma once

#include <memory>
#include <string>

#include "boxes.hpp"
#include "discs.hpp"
#include "joints.hpp"

#if FIXSTEP_BOX2D3_MINOR == 1
#define FIXSTEP_BOX2D3_NS box2d_v3_1
#elif FIXSTEP_BOX2D3_MINOR == 2
#define FIXSTEP_BOX2D3_NS box2d_v3_2
#endif

namespace discs::box2d_v3_1 {
[[nodiscard]] std::unique_ptr<Stepper> make_discs(const Scene& s, int workers, bool sleep);
[[nodiscard]] std::unique_ptr<boxes::BoxStepper> make_boxes(const boxes::BoxScene& s, int workers);
/// joints_box2d3.cpp (the object library joints_box2d3 or joints_box2d32, bench_joints only).
[[nodiscard]] std::unique_ptr<joints::JointStepper> make_joints(const joints::JointScene& s,
                                                                int workers);
[[nodiscard]] std::string version();
[[nodiscard]] double linear_slop();
}  // namespace discs::box2d_v3_1

namespace discs::box2d_v3_2 {
[[nodiscard]] std::unique_ptr<Stepper> make_discs(const Scene& s, int workers, bool sleep);
[[nodiscard]] std::unique_ptr<boxes::BoxStepper> make_boxes(const boxes::BoxScene& s, int workers);
/// joints_box2d3.cpp (the object library joints_box2d3 or joints_box2d32, bench_joints only).
[[nodiscard]] std::unique_ptr<joints::JointStepper> make_joints(const joints::JointScene& s,
                                                                int workers);
[[nodiscard]] std::string version();
[[nodiscard]] double linear_slop();
}  // namespace discs::box2d_v3_2
