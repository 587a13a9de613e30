// The shape solver's manifolds four at a time (engine/core/src/shape_lanes.hpp): the same bits
// as each manifold solved alone through the scalar row kernels, and at every SIMD level.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/shape.hpp"
#include "fixstep/core/simd.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "shape_exact.hpp"
#include "shape_lane_rows.hpp"
#include "shape_rows.hpp"

namespace fixstep {
namespace {

using shape_exact::box_body;

/// Every kind of manifold the sweep meets: boxes landing flat (two-point blocks) and on a
/// corner (one point) on a plane and on each other, capsules, discs with rolling resistance
/// (one at a time), a static box and a kinematic paddle (bodies that do not move under an
/// impulse, read by the lanes, never written), and a wall.
WorldDef tumbling_pile() {
  WorldDef def = WorldDef::empty(Precision::f64, shape_exact::shape_settings(0.6, 0.1));
  def.planes.push_back(PlaneDef{.normal = {0.0, 1.0}, .offset = 0.0, .friction = 0.6});
  def.planes.push_back(PlaneDef{.normal = {1.0, 0.0}, .offset = -3.0, .friction = 0.6});
  for (int i = 0; i < 90; ++i) {
    BodyDef b = box_body(0.25 + 0.02 * (i % 4), 0.2, {0.55 * (i % 10) - 2.6, 0.5 + 0.5 * (i / 10)},
                         i % 5 == 0 ? 0.0 : 0.35 * i);
    if (i % 7 == 3) b.shapes = {make_capsule({-0.2, 0.0}, {0.2, 0.0}, 0.12)};
    if (i % 11 == 5) {
      b.shapes = {make_circle(0.2)};
      b.shapes[0].rolling_resistance = 0.05;
    }
    def.add_body(b);
  }
  BodyDef shelf;
  shelf.type = BodyType::static_body;
  shelf.body.position = {2.5, 1.0};
  shelf.shapes = {make_box(0.6, 0.1)};
  def.add_body(shelf);
  BodyDef paddle;
  paddle.type = BodyType::kinematic;
  paddle.body.position = {-1.0, 0.4};
  paddle.body.angular_velocity = 2.0;
  paddle.shapes = {make_box(0.8, 0.05)};
  def.add_body(paddle);
  return def;
}

/// The state hash after each of `ticks` ticks.
std::vector<std::uint64_t> hashes(int ticks) {
  World w(tumbling_pile());
  std::vector<std::uint64_t> out;
  for (int i = 0; i < ticks; ++i) {
    w.step();
    out.push_back(w.state_hash());
  }
  EXPECT_FALSE(w.fault().has_value());
  EXPECT_GT(w.contact_stats().shape_points, 100u);  // a pile, not a rain
  return out;
}

/// Restores the lanes and the SIMD level when a test ends.
struct Restore {
  SimdLevel level = simd_level();
  ~Restore() {
    detail::shape_lanes::set_lanes_enabled(true);
    set_simd_level(level);
  }
};

TEST(ShapeLanes, FourAtATimeMatchesEachManifoldAloneBitForBit) {
  Restore restore;
  const std::vector<std::uint64_t> lanes = hashes(240);
  detail::shape_lanes::set_lanes_enabled(false);
  const std::vector<std::uint64_t> alone = hashes(240);
  for (std::size_t t = 0; t < lanes.size(); ++t) {
    ASSERT_EQ(lanes[t], alone[t]) << "first differs after tick " << t + 1;
  }
}

TEST(ShapeLanes, EverySimdLevelMatchesBaselineBitForBit) {
  Restore restore;
  set_simd_level(SimdLevel::baseline);
  const std::vector<std::uint64_t> baseline = hashes(240);
  int compared = 0;
  for (const SimdLevel level : {SimdLevel::avx2, SimdLevel::avx512}) {
    if (!simd_supported(level)) continue;
    set_simd_level(level);
    EXPECT_EQ(hashes(240), baseline) << simd_level_name(level);
    ++compared;
  }
  if (compared == 0) GTEST_SKIP() << "this CPU runs the baseline level only";
}

// --- the kernel alone, on rows no world would make ----------------------------------------

bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

/// A block's two rows with random lever arms, masses, targets, impulses and friction; K from
/// them, or (`indefinite`) its coupling k12 negative and larger than both diagonals, so that
/// rounding is not needed for the block solver to find none of its four cases and fall back to the
/// points one after the other.
std::pair<detail::ShapeSolveRow, detail::ShapeSolveRow> random_block(std::mt19937_64& rng,
                                                                     bool indefinite) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  detail::ShapeSolveRow h1, h2;
  const double angle = 3.2 * u(rng);
  h1.nx = h2.nx = std::cos(angle), h1.ny = h2.ny = std::sin(angle);
  h1.ma = h2.ma = u(rng) > -0.5 ? 1.0 + u(rng) * 0.9 : 0.0;  // a quarter against a plane
  h1.ia = h2.ia = h1.ma > 0.0 ? 2.0 + u(rng) : 0.0;
  h1.mb = h2.mb = 1.0 + u(rng) * 0.9, h1.ib = h2.ib = 2.0 + u(rng);
  h1.friction = h2.friction = 0.5 + 0.5 * u(rng);
  for (detail::ShapeSolveRow* h : {&h1, &h2}) {
    h->rna = u(rng), h->rnb = u(rng), h->rta = u(rng), h->rtb = u(rng);
    h->kn = h->ma + h->mb + h->ia * h->rna * h->rna + h->ib * h->rnb * h->rnb;
    h->normal_mass = 1.0 / h->kn;
    h->kt = h->ma + h->mb + h->ia * h->rta * h->rta + h->ib * h->rtb * h->rtb;
    h->tangent_mass = 1.0 / h->kt;
    h->target = u(rng) > 0.0 ? 0.0 : 2.0 * u(rng);
    h->ln = u(rng) > 0.0 ? 0.0 : 3.0 * (1.0 + u(rng)), h->lt = h->friction * h->ln * u(rng);
  }
  h1.k12 = h1.ma + h1.mb + h1.ia * h1.rna * h2.rna + h1.ib * h1.rnb * h2.rnb;
  if (indefinite) h1.k12 = -(2.0 + u(rng)) * std::max(h1.kn, h2.kn);
  const double det = h1.kn * h2.kn - h1.k12 * h1.k12;
  h1.block_mass = {h2.kn / det, -h1.k12 / det, h1.kn / det};
  return {h1, h2};
}

TEST(ShapeLanes, TheBlockKernelGivesTheScalarBitsInEveryCaseAndItsFallback) {
  std::mt19937_64 rng(20261129);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  constexpr int width = detail::shape_lanes::width;
  int fallbacks = 0;
  for (int round = 0; round < 4000; ++round) {
    // Four lanes: their bodies' velocities in slots 0-7, each lane writing its own two.
    std::vector<detail::ShapeMotion> scalar(2 * width), lanes(2 * width);
    for (auto& m : scalar) m = {u(rng), u(rng), u(rng)};
    lanes = scalar;
    detail::shape_lanes::BlockLanes g;
    std::array<std::pair<detail::ShapeSolveRow, detail::ShapeSolveRow>, width> rows;
    for (int l = 0; l < width; ++l) {
      rows[l] = random_block(rng, round % 2 == 1);
      const auto& [h1, h2] = rows[l];
      g.read_a[l] = g.write_a[l] = 2 * l, g.read_b[l] = g.write_b[l] = 2 * l + 1;
      g.nx[l] = h1.nx, g.ny[l] = h1.ny, g.ma[l] = h1.ma, g.ia[l] = h1.ia, g.mb[l] = h1.mb;
      g.ib[l] = h1.ib, g.friction[l] = h1.friction, g.k12[l] = h1.k12;
      g.m11[l] = h1.block_mass[0], g.m12[l] = h1.block_mass[1], g.m22[l] = h1.block_mass[2];
      for (int p = 0; p < 2; ++p) {
        const detail::ShapeSolveRow& h = p == 0 ? h1 : h2;
        auto& q = g.p[p];
        q.rna[l] = h.rna, q.rnb[l] = h.rnb, q.rta[l] = h.rta, q.rtb[l] = h.rtb, q.kn[l] = h.kn;
        q.kt[l] = h.kt, q.normal_mass[l] = h.normal_mass, q.tangent_mass[l] = h.tangent_mass;
        q.target[l] = h.target, q.ln[l] = h.ln, q.lt[l] = h.lt;
      }
    }
    detail::shape_lanes::Lane change{};
    detail::shape_lanes::solve_group(g, lanes.data(), change);
    double expected_change = 0.0;  // the largest |Δλ| K of any row (m/s)
    for (int l = 0; l < width; ++l) {
      auto& [h1, h2] = rows[l];
      const std::array<double, 4> was{h1.ln, h1.lt, h2.ln, h2.lt};
      detail::ShapeMotion a = scalar[2 * l], b = scalar[2 * l + 1];
      detail::shape_rows::solve_friction(h1, a, b);
      detail::shape_rows::solve_friction(h2, a, b);
      {  // whether the block solver finds none of its four cases (shape_rows::solve_block)
        const double k12 = h1.k12, x1 = h1.ln, x2 = h2.ln;
        const double b1 =
            detail::shape_rows::normal_of(h1, a, b) - h1.target - (h1.kn * x1 + k12 * x2);
        const double b2 =
            detail::shape_rows::normal_of(h2, a, b) - h2.target - (k12 * x1 + h2.kn * x2);
        const double y1 = -(h1.block_mass[0] * b1 + h1.block_mass[1] * b2);
        const double y2 = -(h1.block_mass[1] * b1 + h1.block_mass[2] * b2);
        const double z1 = -b1 * h1.normal_mass, z2 = -b2 * h2.normal_mass;
        fallbacks += !(y1 >= 0.0 && y2 >= 0.0) && !(z1 >= 0.0 && k12 * z1 + b2 >= 0.0) &&
                     !(z2 >= 0.0 && k12 * z2 + b1 >= 0.0) && !(b1 >= 0.0 && b2 >= 0.0);
      }
      detail::shape_rows::solve_block(h1, h2, a, b);
      for (int p = 0; p < 2; ++p) {
        const detail::ShapeSolveRow& h = p == 0 ? h1 : h2;
        ASSERT_TRUE(same_bits(g.p[p].ln[l], h.ln)) << "round " << round << " lane " << l;
        ASSERT_TRUE(same_bits(g.p[p].lt[l], h.lt)) << "round " << round << " lane " << l;
        expected_change = std::max({expected_change, std::abs(h.ln - was[2 * p]) * h.kn,
                                    std::abs(h.lt - was[2 * p + 1]) * h.kt});
      }
      for (int k = 0; k < 2; ++k) {
        const detail::ShapeMotion& s = k == 0 ? a : b;
        const detail::ShapeMotion& v = lanes[2 * l + k];
        ASSERT_TRUE(same_bits(s.vx, v.vx) && same_bits(s.vy, v.vy) && same_bits(s.w, v.w))
            << "round " << round << " lane " << l << " body " << k;
      }
    }
    ASSERT_EQ(detail::shape_lanes::largest(change), expected_change) << "round " << round;
  }
  EXPECT_GT(fallbacks, 100);  // the fallback ran, not only the four cases
}

}  // namespace
}  // namespace fixstep
