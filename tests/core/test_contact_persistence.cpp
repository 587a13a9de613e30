// Resting contacts persist while a pile settles (disc_gather.cpp, pair_contact): a contact that
// carried load last tick and now closes by less than the velocity change that load gave it is
// still a resting contact, not an impact of the next tick. Discs falling together have no
// relative acceleration, so without the load in the test such contacts were dropped, their loads
// with them, and caught again as impacts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <numbers>

#include "fixstep/core/components.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "test_bodies.hpp"

namespace fixstep {
namespace {

constexpr double lattice_r = 0.05;  // m

/// Ten rows of 1 kg discs packed hexagonally wall to wall in a box (even rows `wide` discs, odd
/// rows one fewer in the pockets), 1e-6 of a diameter apart, under gravity, inelastic, μ = 0.5,
/// at 60 ticks a second: the lattice bench/discs_scene.cpp times as its settling pile.
WorldDef lattice(std::size_t wide) {
  const double s = 2.0 * lattice_r * (1.0 + 1e-6), h = std::numbers::sqrt3 / 2.0 * s;
  WorldDef def;
  def.settings.dt = 1.0 / 60.0;
  def.settings.contacts = ContactSettings{.restitution = 0.0, .friction = 0.5};
  def.planes.push_back(PlaneDef{.normal = {0, 1}, .offset = 0.0});
  def.planes.push_back(PlaneDef{.normal = {1, 0}, .offset = 0.0});
  def.planes.push_back(PlaneDef{.normal = {-1, 0}, .offset = -double(wide) * s});
  for (std::size_t row = 0; row < 10; ++row) {
    const bool odd = row % 2 == 1;
    for (std::size_t i = 0; i < (odd ? wide - 1 : wide); ++i) {
      const Vec2 at{(odd ? s : s / 2.0) + double(i) * s, s / 2.0 + double(row) * h};
      def.bodies.push_back(test::falling_disc(at, {}, lattice_r));
    }
  }
  return def;
}

// Half a second in, the lattice rests on itself, and from then on its set of touching pairs
// holds: their count changes by no more than a few as the lattice settles, within the slop.
TEST(ContactPersistence, ASettlingLatticeKeepsItsContacts) {
  World w(lattice(60));
  std::size_t touching_least = 0, touching_most = 0;
  for (int t = 0; t < 240; ++t) {
    w.step();
    const ContactStats& c = w.contact_stats();
    if (t < 30) continue;
    touching_least = t == 30 ? c.touching : std::min(touching_least, c.touching);
    touching_most = std::max(touching_most, c.touching);
  }
  // (Without the last tick's load in the test, between 1509 and 1601 pairs touch from tick to
  // tick where the lattice keeps 1710 or 1711.)
  EXPECT_LE(touching_most - touching_least, 3u);
  EXPECT_LE(w.contact_stats().max_overlap, 0.01 * lattice_r);
}

}  // namespace
}  // namespace fixstep
