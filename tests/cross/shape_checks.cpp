// The exact checks of bodies with shapes and joints (shape_exact.hpp, joint_exact.hpp) without
// GoogleTest, for the builds
// that have none: the aarch64 build under qemu and the wasm32 build under node run them as
// ctest cross_shape_checks. Prints each check's measures; exits 1 if any is out of its bounds.
#include <cstdio>

#include "joint_exact.hpp"
#include "shape_exact.hpp"

int main() {
  int failed = 0, measured = 0;
  std::vector<fixstep::shape_exact::Check> all = fixstep::shape_exact::checks();
  for (fixstep::shape_exact::Check& c : fixstep::joint_exact::checks()) all.push_back(std::move(c));
  for (const fixstep::shape_exact::Check& c : all) {
    for (const fixstep::shape_exact::Measure& m : c.run()) {
      ++measured;
      const bool ok = m.holds();
      failed += ok ? 0 : 1;
      std::printf("%s %s: %s = %.17g in [%.17g, %.17g]\n", ok ? "ok" : "FAIL", c.name.c_str(),
                  m.what.c_str(), m.value, m.low, m.high);
    }
  }
  std::printf("%d of %d measures within their bounds\n", measured - failed, measured);
  return failed == 0 ? 0 : 1;
}
