// Candidate pairs recycled from fat boxes (disc_fat.cpp): while every disc's box stays inside
// its fat box the broadphase does not run, and an impact that sends a disc beyond its box asks
// the grid of the fat boxes for its new partners. A world restored from a snapshot (whose
// broadphase holds no grid, or another world's) must find the same partners: its grid is built
// again from the fat boxes. (That the recycled pairs are the broadphase's own is guarded by the
// golden state hashes and the disc tests, which fail when a disc may leave its fat box.)
#include <gtest/gtest.h>

#include <cstdint>

#include "fixstep/core/components.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "test_bodies.hpp"

namespace fixstep {
namespace {

constexpr double cradle_r = 0.05;  // m

/// A row of 12 discs of 1 kg resting on a frictionless floor, 0.05 r apart (their boxes do not
/// overlap), and a ball rolling into them at `speed` m/s (a tenth of a radius a tick at 0.3):
/// every impact sends a disc beyond its box within the tick, into its neighbour (e = 1).
WorldDef cradle(double speed) {
  WorldDef def;
  def.settings.dt = 1.0 / 60.0;
  def.settings.contacts = ContactSettings{.restitution = 1.0, .friction = 0.0};
  def.planes.push_back(PlaneDef{.normal = {0, 1}, .offset = 0.0, .restitution = 0.0});
  for (int i = 0; i <= 12; ++i) {
    const double x = i == 0 ? -0.5 : (i - 1) * 2.05 * cradle_r;
    def.bodies.push_back(test::falling_disc({x, cradle_r}, {i == 0 ? speed : 0.0, 0.0}, cradle_r));
  }
  return def;
}

TEST(FatBoxes, ARestoredWorldFindsTheSamePartnersWithinATick) {
  World w(cradle(0.3));
  World other(cradle(0.45));  // its own broadphase grid, of other boxes
  std::size_t impacts = 0;
  for (int t = 0; t < 200; ++t) {
    WorldSnapshot snap;
    w.save(snap);
    other.restore(snap);
    World fresh(cradle(0.3));
    fresh.restore(snap);
    w.step(), other.step(), fresh.step();
    impacts += w.impacts().size();
    ASSERT_EQ(other.state_hash(), w.state_hash()) << "tick " << t;
    ASSERT_EQ(fresh.state_hash(), w.state_hash()) << "tick " << t;
  }
  EXPECT_GE(impacts, 12u);  // the ball's push went down the row
}

}  // namespace
}  // namespace fixstep
