// Every SIMD level of the stepping sweeps (fixstep/core/simd.hpp) must give the baseline level's
// results bit for bit: a world's state after N ticks may not depend on the CPU it ran on.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/defined_bodies.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/integrators.hpp"
#include "fixstep/core/simd.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_settings.hpp"
#include "world_kernel.hpp"

namespace fixstep {
namespace {

constexpr SimdLevel levels[] = {SimdLevel::baseline, SimdLevel::avx2, SimdLevel::avx512};

/// Restores the level in use when a test ends.
struct LevelGuard {
  SimdLevel saved = simd_level();
  ~LevelGuard() { set_simd_level(saved); }
};

/// Which parts of the force field the bodies declare: each combination is its own compiled
/// sweep (spring shape x damping x constant acceleration).
struct Mix {
  const char* name;
  bool spring, rest_length, damped, accel;
};
constexpr Mix mixes[] = {
    {"spring", true, false, false, false},
    {"spring_damped", true, false, true, false},
    {"spring_damped_gravity", true, false, true, true},
    {"rest_length_damped_force", true, true, true, true},
    {"rest_length", true, true, false, false},
    {"projectile_drag", false, false, true, true},
    {"free", false, false, false, false},
};

/// 1003 bodies (odd: the vector loops' scalar remainders run) with varied parameters; with
/// rest lengths, one body in seven has L = 0 and one sits on its anchor (|d| = 0).
template <class Real>
std::unique_ptr<detail::WorldKernel<Real>> make(const Mix& m, Integrator integrator, int substeps) {
  auto w = std::make_unique<detail::WorldKernel<Real>>(
      WorldSettings{.dt = 1.0 / 60.0, .integrator = integrator, .substeps = substeps});
  for (int j = 0; j < 1003; ++j) {
    BodyDef d;
    d.body.mass = 0.5 + 0.125 * (j % 9);
    d.body.position = {0.3 * (j % 17) - 2.0, 0.2 * (j % 11) + 1.0};
    d.body.velocity = {0.1 * (j % 5) - 0.2, 0.05 * (j % 7)};
    if (m.spring) {
      d.spring =
          SpringDamper{.anchor = {0.25 * (j % 13), -0.5},
                       .stiffness = 2.0 + 3.0 * (j % 6),
                       .damping = m.damped ? 0.1 + 0.05 * (j % 4) : 0.0,
                       .rest_length = m.rest_length && j % 7 != 0 ? 0.5 + 0.1 * (j % 5) : 0.0};
      if (m.rest_length && j == 3) d.body.position = d.spring->anchor;
    } else if (m.damped) {
      d.drag = LinearDrag{0.02 * (j % 5)};
    }
    if (m.accel) {
      d.gravity = Gravity{};
      if (j % 3 == 0) d.constant_force = ConstantForce{{1.5, -0.5}};
    }
    w->create_body(d);
  }
  return w;
}

template <class Real>
std::vector<Real> run(SimdLevel level, const Mix& m, Integrator integrator, int substeps) {
  set_simd_level(level);
  auto w = make<Real>(m, integrator, substeps);
  for (int t = 0; t < 120; ++t) {
    // A push on some ticks: the sweep folds it into the constant acceleration.
    w->step(TickInput{.tick = std::uint64_t(t), .push = t % 40 < 10 ? Vec2{0.0, 2.0} : Vec2{}});
  }
  std::vector<Real> state;
  for (auto field : {w->x(), w->y(), w->vx(), w->vy()})
    state.insert(state.end(), field.begin(), field.end());
  return state;
}

template <class Real>
void expect_levels_identical() {
  const LevelGuard guard;
  int compared = 0;
  for (const Mix& m : mixes) {
    for (Integrator integrator : all_integrators) {
      const int substeps = integrator == Integrator::rk4 ? 2 : 1;
      const auto reference = run<Real>(SimdLevel::baseline, m, integrator, substeps);
      for (SimdLevel level : levels) {
        if (level == SimdLevel::baseline || !simd_supported(level)) continue;
        const auto state = run<Real>(level, m, integrator, substeps);
        ASSERT_EQ(state.size(), reference.size());
        std::size_t differ = 0;
        for (std::size_t i = 0; i < state.size(); ++i) {
          differ += std::memcmp(&state[i], &reference[i], sizeof(Real)) != 0;
          ASSERT_TRUE(std::isfinite(state[i]));
        }
        EXPECT_EQ(differ, 0u) << simd_level_name(level) << " vs baseline, " << m.name << ", "
                              << integrator_name(integrator) << ", f" << 8 * sizeof(Real);
        ++compared;
      }
    }
  }
  if (compared == 0) GTEST_SKIP() << "this CPU runs the baseline level only";
}

TEST(Simd, EveryLevelMatchesBaselineBitForBitF64) {
  expect_levels_identical<double>();
}
TEST(Simd, EveryLevelMatchesBaselineBitForBitF32) {
  expect_levels_identical<float>();
}

TEST(Simd, TheRuntimeGuardFiresAtTheSameTickAtEveryLevel) {
  const LevelGuard guard;
  // 1003 bodies, one of them (index 500, mid-vector) on a spring beyond semi-implicit Euler's
  // bound: every level must report it at the baseline's tick.
  auto fault_at = [](SimdLevel level) {
    set_simd_level(level);
    detail::WorldKernel<double> w(WorldSettings{.dt = 0.1});
    for (int j = 0; j < 1003; ++j) {
      BodyDef d;
      d.body.position = {1.0, 0.0};
      d.spring = SpringDamper{.stiffness = j == 500 ? 900.0 : 1.0};
      w.create_body(d);
    }
    for (int t = 0; t < 100 && !w.fault(); ++t) w.step();
    return w.fault();
  };
  const auto reference = fault_at(SimdLevel::baseline);
  ASSERT_TRUE(reference.has_value());
  EXPECT_EQ(reference->body, fixstep::defined_entity(500));
  for (SimdLevel level : levels) {
    if (!simd_supported(level)) continue;
    const auto f = fault_at(level);
    ASSERT_TRUE(f.has_value()) << simd_level_name(level);
    EXPECT_EQ(f->body, reference->body) << simd_level_name(level);
    EXPECT_EQ(f->tick, reference->tick) << simd_level_name(level);
    EXPECT_EQ(f->field, reference->field) << simd_level_name(level);
  }
}

TEST(Simd, BaselineIsAlwaysSupportedAndLevelsCanBeChosen) {
  const LevelGuard guard;
  EXPECT_TRUE(simd_supported(SimdLevel::baseline));
  for (SimdLevel level : levels) {
    if (simd_supported(level)) {
      set_simd_level(level);
      EXPECT_EQ(simd_level(), level);
    } else {
      EXPECT_THROW(set_simd_level(level), std::invalid_argument) << simd_level_name(level);
    }
  }
}

TEST(Simd, DefaultIsTheWidestSupportedLevel) {
  // A process starts at the widest level; the other tests restore it when they end.
  SimdLevel widest = SimdLevel::baseline;
  for (SimdLevel level : levels) {
    if (simd_supported(level)) widest = level;
  }
  EXPECT_EQ(simd_level(), widest);
}

}  // namespace
}  // namespace fixstep
