// The exact checks of bodies with shapes (shape_exact.hpp) without GoogleTest, for the builds
// that have none: the aarch64 build under qemu and the wasm32 build under node run them as
// ctest cross_shape_checks. Prints each check's measures; exits 1 if any is out of its bounds.
#include <cstdio>

#include "shape_exact.hpp"

int main() {
  int failed = 0, measured = 0;
  for (const fixstep::shape_exact::Check& c : fixstep::shape_exact::checks()) {
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
