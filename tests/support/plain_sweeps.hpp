// For a test's scope: the shape contacts' velocity sweeps without their conjugate steps
// (sweep_conjugate.hpp), plain projected Gauss–Seidel sweeps.
#pragma once

#include "sweep_conjugate.hpp"

namespace fixstep::test {

struct PlainSweeps {
  PlainSweeps() { detail::set_sweeps_conjugate(false); }
  ~PlainSweeps() { detail::set_sweeps_conjugate(true); }
  PlainSweeps(const PlainSweeps&) = delete;
  PlainSweeps& operator=(const PlainSweeps&) = delete;
};

}  // namespace fixstep::test
