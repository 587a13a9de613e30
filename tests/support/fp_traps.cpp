// Floating-point traps for the physics tests of Debug builds (the asan preset is one): an
// invalid operation (0/0, inf - inf, sqrt(-1), ...) or a division by zero raises SIGFPE at the
// instruction instead of quietly producing a NaN or an infinity that spreads. Linked into the
// test programs that do not render: Mesa's llvmpipe threads inherit the FP environment and
// are not written to run with traps.
#include <gtest/gtest.h>

#if defined(FIXSTEP_FP_TRAPS) && defined(__GLIBC__)
#include <fenv.h>

namespace {

class FpTraps : public ::testing::Environment {
 public:
  void SetUp() override {
    std::feclearexcept(FE_ALL_EXCEPT);
    ASSERT_NE(feenableexcept(FE_INVALID | FE_DIVBYZERO), -1) << "feenableexcept failed";
  }
  void TearDown() override { fedisableexcept(FE_INVALID | FE_DIVBYZERO); }
};

[[maybe_unused]] ::testing::Environment* const fp_traps =
    ::testing::AddGlobalTestEnvironment(new FpTraps);

}  // namespace
#endif
