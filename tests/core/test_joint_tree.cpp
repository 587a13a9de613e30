// The joints' direct solve (joint_tree.hpp): which joints join the forest, its solution against
// K = J M⁻¹ Jᵀ assembled row by row, its trees solved alone, and a swinging chain held to its
// tolerance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <optional>
#include <random>
#include <vector>

#include "fixstep/core/world.hpp"
#include "joint_checks.hpp"
#include "joint_solver.hpp"
#include "joint_tree.hpp"
#include "shape_exact.hpp"
#include "shape_world.hpp"
#include "world_kernel.hpp"

namespace fixstep {
namespace {

using detail::JointBodies;
using detail::JointRecord;
using detail::JointTree;
using detail::ShapedBody;
using joint_checks::revolute;
constexpr std::uint32_t world = JointRecord::none;

/// Bodies 0–9 a chain from the world with a branch at body 2; 10–13 a chain of their own,
/// free; 14 does not move; 15 turns but does not translate (its joint's point would have one
/// row it cannot move: left to the joint's own rows), 16 translates but does not turn.
std::vector<ShapedBody> bodies() {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> unit(0.2, 5.0);
  std::vector<ShapedBody> b(17);
  for (ShapedBody& s : b) s.inv_mass = unit(random), s.inv_inertia = unit(random);
  b[14].inv_mass = b[14].inv_inertia = 0.0;
  b[15].inv_mass = 0.0;
  b[16].inv_inertia = 0.0;
  return b;
}

std::vector<JointRecord> joints() {
  std::vector<JointRecord> j;
  j.push_back(revolute(world, 0));
  for (std::uint32_t k = 1; k < 6; ++k) j.push_back(revolute(k - 1, k));
  for (std::uint32_t k = 6; k < 10; ++k) j.push_back(revolute(k == 6 ? 2 : k - 1, k));
  j.push_back(revolute(3, 8));       // closes a loop: 3 and 8 are one tree already
  j.push_back(revolute(9, 14));      // to a body that does not move: a second way to the ground
  j.push_back(revolute(world, 14));  // nothing that moves
  for (std::uint32_t k = 11; k < 14; ++k) j.push_back(revolute(k - 1, k));
  j.push_back(revolute(13, 15));
  j.push_back(revolute(16, 10));
  JointRecord prismatic = revolute(5, 16);
  prismatic.def.type = JointType::prismatic;
  j.push_back(prismatic);
  JointRecord broken = revolute(4, 15);
  broken.broken = true;
  j.push_back(broken);
  return j;
}

/// The forest of every joint of `j` (the list 0, 1, 2, ...; the numbers in `numbered`).
void build_all(JointTree& tree, std::vector<JointRecord>& j, std::span<const ShapedBody> b,
               JointBodies& numbered) {
  std::vector<std::uint32_t> all(j.size());
  std::iota(all.begin(), all.end(), 0U);
  numbered.build(j, all, b.size());
  tree.build(j, all, b, numbered);
}

/// bodies() and joints(), and the forest of every joint built.
struct Forest {
  std::vector<ShapedBody> b = bodies();
  std::vector<JointRecord> j = joints();
  JointTree tree;
  JointBodies numbered;
  Forest() { build_all(tree, j, b, numbered); }
};

TEST(JointTree, TakesTheRevoluteJointsOfAForestAndLeavesTheLoopsToTheirOwnRows) {
  Forest f;
  std::vector<ShapedBody>& b = f.b;
  std::vector<JointRecord>& j = f.j;
  JointTree& tree = f.tree;
  JointBodies& numbered = f.numbered;
  std::vector<std::uint32_t> expected;
  for (std::uint32_t k = 0; k < j.size(); ++k) {
    const bool loop = k == 10 || k == 11, still = k == 12, other = k == 16 || k >= 18;
    EXPECT_EQ(j[k].direct, !(loop || still || other)) << "joint " << k;
    if (j[k].direct) expected.push_back(k);
  }
  EXPECT_EQ(std::vector<std::uint32_t>(tree.members().begin(), tree.members().end()), expected);
  // Of a list of joints, the forest of those alone: joint 11 closed a loop with 10, which is
  // not listed; those not listed keep their flag. The numbers are made again for the list.
  const std::vector<std::uint32_t> listed = {2, 3, 11, 13};
  for (JointRecord& r : j) r.direct = true;
  numbered.build(j, listed, b.size());
  tree.build(j, listed, b, numbered);
  EXPECT_EQ(std::vector<std::uint32_t>(tree.members().begin(), tree.members().end()), listed);
  EXPECT_TRUE(j[10].direct && j[12].direct) << "not listed: left as they were";
}

/// The largest component of K λ − rhs over the forest of joints(), K assembled independently:
/// row k of J M⁻¹ Jᵀ is the velocity error every member's impulse λ (and angular impulse, for
/// members with an angle row: two of every three when `angles`) gives member k's two ends (Ċ_k
/// of the impulses alone: the point's velocity, and ω_B − ω_A for an angle row). The angle
/// row asked of the member from body 16, which does not turn, to body 10 is left out: its
/// angular impulse must be 0.
double worst_residual(bool angles) {
  Forest f;
  std::vector<ShapedBody>& b = f.b;
  std::vector<JointRecord>& j = f.j;
  JointTree& tree = f.tree;
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> arm(-0.7, 0.7), value(-3.0, 3.0);
  const auto members = tree.members();
  for (std::size_t k = 0; k < members.size(); ++k) {
    JointRecord& r = j[members[k]];
    r.ra = {arm(random), arm(random)}, r.rb = {arm(random), arm(random)};
    tree.arms()[k] = {r.ra, r.rb};
    tree.angle_rows()[k] = angles && k % 3 != 2 ? 1 : 0;
  }
  std::vector<Vec2> rhs(members.size());
  std::vector<double> angle_rhs(members.size());
  for (std::size_t k = 0; k < members.size(); ++k) {
    rhs[k] = {value(random), value(random)}, angle_rhs[k] = value(random);
  }
  tree.factor();
  std::copy(rhs.begin(), rhs.end(), tree.rhs().begin());
  std::copy(angle_rhs.begin(), angle_rhs.end(), tree.angle_rhs().begin());
  tree.solve(tree.rhs(), tree.angle_rhs());
  const std::vector<Vec2> lambda(tree.rhs().begin(), tree.rhs().end());
  const std::vector<double> turn(tree.angle_rhs().begin(), tree.angle_rhs().end());

  struct Motion {
    Vec2 v{};
    double w = 0.0;
  };
  std::vector<Motion> dv(b.size());
  auto give = [&](std::uint32_t body, Vec2 p, Vec2 r, double l) {
    if (body == world) return;
    dv[body].v = dv[body].v + b[body].inv_mass * p;
    dv[body].w += b[body].inv_inertia * (cross(r, p) + l);
  };
  for (std::size_t k = 0; k < members.size(); ++k) {
    const JointRecord& r = j[members[k]];
    const double l = tree.angle_rows()[k] != 0 ? turn[k] : 0.0;
    give(r.a, -1.0 * lambda[k], r.ra, -l);
    give(r.b, lambda[k], r.rb, l);
  }
  auto point = [&](std::uint32_t body, Vec2 r) {
    if (body == world) return Vec2{};
    return dv[body].v + Vec2{-dv[body].w * r.y, dv[body].w * r.x};
  };
  auto spin = [&](std::uint32_t body) { return body == world ? 0.0 : dv[body].w; };
  double worst = 0.0;
  for (std::size_t k = 0; k < members.size(); ++k) {
    const JointRecord& r = j[members[k]];
    const Vec2 cdot = point(r.b, r.rb) - point(r.a, r.ra);
    worst = std::max({worst, std::abs(cdot.x - rhs[k].x), std::abs(cdot.y - rhs[k].y)});
    EXPECT_EQ(tree.angle_row_kept(k), tree.angle_rows()[k] != 0 && r.a != 16) << "member " << k;
    if (tree.angle_rows()[k] != 0 && r.a == 16) {
      worst = std::max(worst, std::abs(turn[k]));
    } else if (tree.angle_rows()[k] != 0) {
      worst = std::max(worst, std::abs(spin(r.b) - spin(r.a) - angle_rhs[k]));
    }
  }
  return worst;
}

/// Arms and a right-hand side for `tree`'s forest drawn from one seed (the same for the same
/// members), factored.
void draw(JointTree& tree) {
  std::mt19937_64 random(5);
  std::uniform_real_distribution<double> arm(-0.7, 0.7), value(-3.0, 3.0);
  const auto members = tree.members();
  for (std::size_t k = 0; k < members.size(); ++k) {
    tree.arms()[k] = {Vec2{arm(random), arm(random)}, Vec2{arm(random), arm(random)}};
    tree.rhs()[k] = {value(random), value(random)};
  }
  tree.factor();
}

/// λ of `tree`'s forest for draw()'s arms and right-hand side.
std::vector<Vec2> solved(JointTree& tree) {
  draw(tree);
  tree.solve(tree.rhs());
  return {tree.rhs().begin(), tree.rhs().end()};
}

// A build that finds the members' ends as the last one left them keeps its nodes and takes
// the bodies' masses now; one that finds them changed orders the forest again. Either way the
// forest solves as one built afresh, bit for bit.
TEST(JointTree, ABuildKeepsItsOrderOnlyWhileTheEndsStay) {
  std::vector<ShapedBody> b = bodies();
  std::vector<JointRecord> j = joints();
  JointTree kept;
  JointBodies numbered;
  build_all(kept, j, b, numbered);
  (void)solved(kept);
  auto against_fresh = [&](const char* what) {
    build_all(kept, j, b, numbered);
    const std::vector<Vec2> lambda = solved(kept);
    std::vector<JointRecord> j2 = j;
    JointTree fresh;
    JointBodies numbered2;
    build_all(fresh, j2, b, numbered2);
    ASSERT_TRUE(std::equal(kept.members().begin(), kept.members().end(), fresh.members().begin(),
                           fresh.members().end()))
        << what;
    const std::vector<Vec2> expected = solved(fresh);
    for (std::size_t k = 0; k < lambda.size(); ++k) {
      EXPECT_EQ(lambda[k].x, expected[k].x) << what << ", member " << k;
      EXPECT_EQ(lambda[k].y, expected[k].y) << what << ", member " << k;
    }
  };
  b[3].inv_mass *= 3.0, b[7].inv_inertia *= 0.25;  // the same ends, other masses
  against_fresh("masses changed");
  j[4].broken = true;  // the chain cut between bodies 3 and 4: body 4 on starts a tree
  against_fresh("a joint broken");
  j[4].broken = false;
  against_fresh("the joint mended");
  j[13].b = 12;  // as many members, but joint 13 from body 10 to 12 where it held 11
  against_fresh("an end moved");
  for (JointRecord& r : j) r.broken = true;  // no forest, then the same again
  against_fresh("every joint broken");
  for (JointRecord& r : j) r.broken = false;
  j[joints().size() - 1].broken = true;
  j[13].b = 11;
  against_fresh("as at first");
}

// Solving the trees flagged active gives each of their members the bits of the whole forest's
// solve and leaves the other trees' entries as they were: a tree within its tolerance is left
// alone while another is solved.
TEST(JointTree, SolvesTheActiveTreesAloneWithTheWholeSolvesBits) {
  Forest f;
  JointTree& tree = f.tree;
  ASSERT_EQ(tree.trees(), 2u);  // bodies 0–9 from the world, 10–13 and 16 free
  const std::vector<Vec2> whole = solved(tree);
  for (const int pattern : {0, 1, 2, 3}) {  // which of the two trees are active
    SCOPED_TRACE(pattern);
    const std::vector<std::uint8_t> active{static_cast<std::uint8_t>(pattern & 1),
                                           static_cast<std::uint8_t>(pattern >> 1)};
    draw(tree);
    const std::vector<Vec2> given(tree.rhs().begin(), tree.rhs().end());
    tree.solve(tree.rhs(), {}, JointTree::whole, active);
    for (std::size_t k = 0; k < given.size(); ++k) {
      const Vec2 expected = active[tree.tree_of(k)] != 0 ? whole[k] : given[k];
      EXPECT_EQ(tree.rhs()[k].x, expected.x) << "member " << k;
      EXPECT_EQ(tree.rhs()[k].y, expected.y) << "member " << k;
    }
  }
}

TEST(JointTree, SolvesTheForestsPointRowsAsTheAssembledSystemDoes) {
  EXPECT_LT(worst_residual(false), 1e-12) << "K λ − rhs, the largest component (m/s)";
}

// A limit the joint is past joins the forest's solve as a third row of its joint.
TEST(JointTree, SolvesAngleRowsWithThePointRowsAsTheAssembledSystemDoes) {
  EXPECT_LT(worst_residual(true), 1e-12) << "K λ − rhs, the largest component (m/s, rad/s)";
}

/// A chain's links: boxes 0.5 m long and 2 · `half_width` m across, `mass` kg each, under
/// gravity `g` m/s² downwards.
struct ChainLinks {
  double half_width = 0.05, mass = 1.0, g = 9.81;
};
/// bench/joints_scene.cpp's chain (Box2D's density, 1 kg/m², and its gravity).
constexpr ChainLinks bench_links{.half_width = 0.0625, .mass = 0.0625, .g = 10.0};

/// A horizontal chain of `n` boxes hinged end to end, the first to the world at the
/// origin, released to swing down under gravity.
struct SwingingChain {
  std::unique_ptr<detail::WorldKernel<double>> world;
  std::vector<Entity> links;
  /// `limit` (rad): each joint's relative angle held within ± it (none: free).
  explicit SwingingChain(int n, std::optional<double> limit = std::nullopt,
                         const WorldSettings& settings = shape_exact::shape_settings(0.6),
                         ChainLinks kind = {})
      : world(std::make_unique<detail::WorldKernel<double>>(settings)) {
    Entity before{};
    for (int i = 0; i < n; ++i) {
      BodyDef link =
          shape_exact::box_body(0.25, kind.half_width, {0.25 + 0.5 * i, 0.0}, 0.0, kind.mass);
      link.gravity = Gravity{{0.0, -kind.g}};
      const Entity box = world->create_body(link);
      JointDef def{
          .type = JointType::revolute, .body_a = before, .body_b = box, .anchor = {0.5 * i, 0.0}};
      if (limit) def.lower = -*limit, def.upper = *limit;
      world->create_joint(def, "link");
      links.push_back(box);
      before = box;
    }
  }
  /// How far past ± `limit` the deepest joint's relative angle is (rad; 0 within).
  [[nodiscard]] double past(double limit) const {
    double most = 0.0, before = 0.0;  // the angle of the body before (the world's: 0)
    for (const Entity e : links) {
      const double angle = world->body(e).angle;
      most = std::max(most, std::abs(angle - before) - limit);
      before = angle;
    }
    return most;
  }
  /// The largest distance between a joint's anchor as carried by each of its bodies (m).
  [[nodiscard]] double separation() const {
    double most = 0.0;
    Vec2 end{};  // the anchor as the body before carries it (the world's: the origin)
    for (const Entity e : links) {
      const auto& s = world->body(e);
      const Vec2 u{std::cos(s.angle), std::sin(s.angle)};
      const Vec2 near = s.position - 0.25 * u;
      most = std::max(most, std::hypot(near.x - end.x, near.y - end.y));
      end = s.position + 0.25 * u;
    }
    return most;
  }
};

// Solved a joint at a time, the swinging 100-link chain's joints came apart by centimetres
// (the errors of a chain move along it one link a sweep); solved at once they hold.
TEST(JointTree, ASwingingChainOfAHundredLinksHoldsItsJointsToAMicrometre) {
  SwingingChain chain(100);
  double worst = 0.0;
  for (int t = 0; t < 300; ++t) {
    chain.world->step();
    worst = std::max(worst, chain.separation());
  }
  EXPECT_LT(worst, 1e-6) << "the largest anchor separation over 300 ticks (m)";
  const double tip = chain.world->body(chain.links.back()).position.y;
  EXPECT_LT(tip, -10.0) << "the chain swung down";
}

// Run on, the same chain whips: its last links turn about a radian a tick. The sweeps that
// keep gave their impulses along the start's gradient, which raised its energy in each whip,
// and their chord steps on positions only diverged: the chain came apart (anchors 24 m apart
// at tick 589, its energy growing from there). With the impulses of a joint that turns fast
// along the gradient now, and a chord step that did not shrink the error followed by one
// factored at the poses now, it holds and its energy never rises over its start's.
TEST(JointTree, ASwingingChainOfAHundredLinksHoldsThroughItsWhip) {
  SwingingChain chain(100);
  const double start = chain.world->energy().total();
  double worst = 0.0, gained = 0.0;
  for (int t = 0; t < 3600; ++t) {
    chain.world->step();
    worst = std::max(worst, chain.separation());
    gained = std::max(gained, chain.world->energy().total() - start);
  }
  EXPECT_LT(worst, 1e-3) << "the largest anchor separation over 60 s (m)";
  EXPECT_LT(gained, 1e-6) << "the most energy over the start's, over 60 s (J)";
}

// With fewer position iterations than the default (Box2D v2.4's 8 and 3, or none), the joints'
// own projection of the tick's error still runs until it converges, up to ten steps: cut to
// three or four, the chain came apart as its last links whipped (anchors 0.19 m apart at tick
// 195). Past its second whip (tick 962), nearly straight, a full Newton step of that
// projection can grow the error instead: it is taken back and made shorter (a line search).
// Ended there instead, the chain came apart at 3 (6.9 m) and held within 0.2 to 1.6 mm at the
// others: the push-out's few chord steps carried the rest into the next tick.
TEST(JointTree, ASwingingChainHoldsWithFewPositionIterations) {
  for (const int position : {0, 1, 2, 3, 4}) {
    WorldSettings settings = shape_exact::shape_settings(0.6);
    settings.contacts->velocity_iterations = 8;
    settings.contacts->position_iterations = position;
    SwingingChain chain(100, std::nullopt, settings, bench_links);
    const double start = chain.world->energy().total();
    double worst = 0.0, gained = 0.0;
    for (int t = 0; t < 1200; ++t) {
      chain.world->step();
      worst = std::max(worst, chain.separation());
      gained = std::max(gained, chain.world->energy().total() - start);
    }
    EXPECT_LT(worst, 1e-6) << "the largest anchor separation over 1200 ticks (m), " << position
                           << " position iterations";
    EXPECT_LT(gained, 1e-6) << "the most energy over the start's (J), " << position
                            << " position iterations";
  }
}

// The same chain at 8 and 3 iterations beside two boxes held apart by a distance joint, a
// joint outside the forest: it holds, its steps searched as above, while that joint holds no
// forest body. (Joined to the chain's last link instead, the joint turns the search off:
// taking a step back would undo its own corrections of that link.)
TEST(JointTree, AChainBesideAJointOutsideTheForestStillHoldsWithFewIterations) {
  WorldSettings settings = shape_exact::shape_settings(0.6);
  settings.contacts->velocity_iterations = 8;
  settings.contacts->position_iterations = 3;
  SwingingChain chain(100, std::nullopt, settings, bench_links);
  auto& w = *chain.world;
  const Entity a = w.create_body(shape_exact::box_body(0.25, 0.25, {-200.0, 0.0}));
  const Entity b = w.create_body(shape_exact::box_body(0.25, 0.25, {-198.0, 0.0}));
  w.create_joint({.type = JointType::distance,
                  .body_a = a,
                  .body_b = b,
                  .anchor = {-200.0, 0.0},
                  .anchor_b = Vec2{-198.0, 0.0}},
                 "strut");
  double worst = 0.0;
  for (int t = 0; t < 1200; ++t) {
    w.step();
    worst = std::max(worst, chain.separation());
  }
  EXPECT_LT(worst, 1e-6) << "the chain's largest anchor separation over 1200 ticks (m)";
  EXPECT_GT(w.shape_world()->kept_step_cuts(), 0u) << "no step was taken back";

  SwingingChain joined(100, std::nullopt, settings, bench_links);
  const Entity c = joined.world->create_body(shape_exact::box_body(0.25, 0.25, {52.0, 0.0}));
  joined.world->create_joint({.type = JointType::distance,
                              .body_a = joined.links.back(),
                              .body_b = c,
                              .anchor = {50.0, 0.0},
                              .anchor_b = Vec2{52.0, 0.0}},
                             "strut");
  for (int t = 0; t < 1200; ++t) joined.world->step();
  EXPECT_EQ(joined.world->shape_world()->kept_step_cuts(), 0u)
      << "a step taken back where a joint outside the forest holds a forest body";
}

// A chain held out from a wall by its joints' limits (each ±0.05 rad): gravity bends every
// joint against its limit, hardest near the wall. The limits past which a joint is are solved
// on positions with the forest's anchors, so that correcting one does not undo the other; one
// joint at a time beside the forest's solve, the chain sagged 0.6 rad past them.
TEST(JointTree, AChainHeldOutByItsLimitsStaysWithinThem) {
  constexpr double limit = 0.05;
  SwingingChain chain(30, limit);
  double worst = 0.0;
  for (int t = 0; t < 120; ++t) {
    chain.world->step();
    worst = std::max(worst, chain.past(limit));
  }
  // Box2D v2.4's slop (joint_angular_slop, 2°) is left on positions, and the velocity rows
  // stop the rest; 0.01 rad of rounding.
  EXPECT_LT(worst, detail::joint_angular_slop + 0.01)
      << "the deepest past a limit over 120 ticks (rad)";
  EXPECT_LT(chain.separation(), 1e-6) << "the largest anchor separation at the end (m)";
}

}  // namespace
}  // namespace fixstep
