// The functions of one Box2D v3 release's steppers (discs_box2d3.cpp, boxes_box2d3.cpp), in a
// namespace per release: both sources are compiled once per release (bench/box2d3.cmake, with
// FIXSTEP_BOX2D3_MINOR 1 or 2) and defines the functions of FIXSTEP_BOX2D3_NS;
// box2d3_peers.cpp calls the releases that were built. Internal to bench/.
#pragma once

#include <memory>
#include <string>

#include "boxes.hpp"
#include "discs.hpp"

#if FIXSTEP_BOX2D3_MINOR == 1
#define FIXSTEP_BOX2D3_NS box2d_v3_1
#elif FIXSTEP_BOX2D3_MINOR == 2
#define FIXSTEP_BOX2D3_NS box2d_v3_2
#endif

namespace discs::box2d_v3_1 {
[[nodiscard]] std::unique_ptr<Stepper> make_discs(const Scene& s, int workers);
[[nodiscard]] std::unique_ptr<boxes::BoxStepper> make_boxes(const boxes::BoxScene& s, int workers);
[[nodiscard]] std::string version();
[[nodiscard]] double linear_slop();
}  // namespace discs::box2d_v3_1

namespace discs::box2d_v3_2 {
[[nodiscard]] std::unique_ptr<Stepper> make_discs(const Scene& s, int workers);
[[nodiscard]] std::unique_ptr<boxes::BoxStepper> make_boxes(const boxes::BoxScene& s, int workers);
[[nodiscard]] std::string version();
[[nodiscard]] double linear_slop();
}  // namespace discs::box2d_v3_2
