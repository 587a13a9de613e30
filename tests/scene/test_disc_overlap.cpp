// Discs overlapping where they start: first_disc_overlap against a brute-force search, its
// exemptions and its time on a million-disc pile, and the scene loader's located error; the
// generators' discs (a ball pit, a Galton board's static pegs).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/disc_overlap.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"
#include "fixstep/scene/scene.hpp"
#include "link_between.hpp"

namespace fixstep {
namespace {

BodyDef disc(double x, double y, double r, BodyType type = BodyType::dynamic) {
  BodyDef d;
  d.type = type;
  d.body.position = {x, y};
  d.collider = Collider{.radius = r};
  return d;
}

using Pair = std::optional<std::pair<std::size_t, std::size_t>>;

TEST(DiscOverlap, FindsAPairAndLeavesTouchingDiscsAlone) {
  std::vector<BodyDef> b{disc(0, 0, 1), disc(5, 0, 1), disc(1.5, 0.5, 1)};
  EXPECT_EQ(first_disc_overlap(b, {}), Pair({0, 2}));
  EXPECT_NEAR(disc_overlap_depth(b[0], b[2]), 2.0 - std::hypot(1.5, 0.5), 1e-15);
  b[2].body.position = {2.0, 0.0};  // touching exactly
  EXPECT_EQ(first_disc_overlap(b, {}), std::nullopt);
  // A row of touching balls at start + i * spacing: the distances round a little short of
  // 2r (0.2 * 3 - 0.2 * 2 = 0.19999999999999996), which is not an overlap.
  std::vector<BodyDef> row;
  for (int i = 0; i < 200; ++i) row.push_back(disc(-7.3 + 0.2 * i, 3.1 + 0.2 * i, 0.1));
  for (int i = 0; i < 200; ++i) row.push_back(disc(-7.3 + 0.2 * i, 100.0, 0.1));
  EXPECT_EQ(first_disc_overlap(row, {}), std::nullopt);
  row.push_back(disc(-7.3 + 0.2 * 50, 100.0 + 0.1999, 0.1));  // 0.1 mm into row[250] alone
  EXPECT_EQ(first_disc_overlap(row, {}), Pair({250, 400}));
}

TEST(DiscOverlap, LinkedPairsNonCollidingDiscsAndTwoAnchorsAreExempt) {
  std::vector<BodyDef> b{disc(0, 0, 1), disc(0.5, 0, 1)};
  const std::vector<LinkDef> link{fixstep::test::link_between(1, 0, LinkSpring{1.0, 0.0, 0.0})};
  EXPECT_EQ(first_disc_overlap(b, link), std::nullopt);  // collideConnected = false
  EXPECT_EQ(first_disc_overlap(b, {}), Pair({0, 1}));
  b[1].collider->collide = false;
  EXPECT_EQ(first_disc_overlap(b, {}), std::nullopt);
  b[1].collider->collide = true;
  b[0].type = BodyType::static_body;
  EXPECT_EQ(first_disc_overlap(b, {}), Pair({0, 1}));  // static against dynamic: counted
  b[1].type = BodyType::kinematic;
  EXPECT_EQ(first_disc_overlap(b, {}), std::nullopt);  // two anchors never touch
  BodyDef no_disc = disc(0, 0, 1);
  no_disc.collider.reset();
  b = {no_disc, disc(0, 0, 1)};
  EXPECT_EQ(first_disc_overlap(b, {}), std::nullopt);
}

TEST(DiscOverlap, OnlyWithContactsOnInAWorldDef) {
  WorldDef def;
  def.bodies = {disc(0, 0, 1), disc(0.5, 0, 1)};
  EXPECT_EQ(first_disc_overlap(def), std::nullopt);
  def.settings.contacts = ContactSettings{};
  EXPECT_EQ(first_disc_overlap(def), Pair({0, 1}));
}

TEST(DiscOverlap, RefusesNonFiniteDiscsAndLinksOutOfRange) {
  std::vector<BodyDef> b{disc(0, 0, 1), disc(NAN, 0, 1)};
  EXPECT_THROW((void)first_disc_overlap(b, {}), std::invalid_argument);
  b[1] = disc(3, 0, 0.0);
  EXPECT_THROW((void)first_disc_overlap(b, {}), std::invalid_argument);
  b[1] = disc(3, 0, 1);
  const std::vector<LinkDef> bad{fixstep::test::link_between(0, 2)};
  EXPECT_THROW((void)first_disc_overlap(b, bad), std::invalid_argument);
}

TEST(DiscOverlap, AgreesWithEveryPairCheckedOnRandomScenes) {
  // Mixed radii (0.05 .. 1 m), types, collide flags and links; sparse enough that about half
  // the scenes have no overlap. The sweep must find one exactly when some pair overlaps.
  std::uint64_t state = 12345;
  auto uniform = [&] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return double(state >> 11) * 0x1p-53;
  };
  int with = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const std::size_t n = 2 + std::size_t(uniform() * 60);
    const double size = 6.0 + 40.0 * uniform();
    std::vector<BodyDef> b;
    for (std::size_t i = 0; i < n; ++i) {
      const double t = uniform();
      b.push_back(disc(size * uniform(), size * uniform(), 0.05 + 0.95 * uniform() * uniform(),
                       t < 0.7    ? BodyType::dynamic
                       : t < 0.85 ? BodyType::static_body
                                  : BodyType::kinematic));
      b.back().collider->collide = uniform() > 0.1;
    }
    std::vector<LinkDef> links;
    for (std::size_t l = 0; l < n / 3; ++l) {
      const std::size_t a = std::size_t(uniform() * n), c = std::size_t(uniform() * n);
      if (a != c) links.push_back(fixstep::test::link_between(a, c, LinkSpring{}));
    }
    auto eligible = [&](std::size_t i, std::size_t j) {
      for (const LinkDef& l : links) {
        const std::size_t la = l.body_a.slot(), lb = l.body_b.slot();
        if ((la == i && lb == j) || (la == j && lb == i)) return false;
      }
      return discs_may_touch(b[i], b[j]) && disc_overlap_depth(b[i], b[j]) > 1e-9;
    };
    bool any = false;
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = i + 1; j < n; ++j) any = any || eligible(i, j);
    }
    const Pair found = first_disc_overlap(b, links);
    ASSERT_EQ(found.has_value(), any) << "trial " << trial;
    if (found) {
      EXPECT_LT(found->first, found->second);
      EXPECT_TRUE(eligible(found->first, found->second)) << "trial " << trial;
    }
    with += any;
  }
  EXPECT_GT(with, 50);
  EXPECT_LT(with, 250);
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

TEST(DiscOverlap, APileAtOnePointAndALatticeTakeBoundedTime) {
  // 2·10^5 discs (10^6 take 0.16 s in the CI build: see disc_overlap.hpp): a pile at one point
  // stops at its first pair; static pegs at one point are never compared with each other.
  std::vector<BodyDef> pile(200000, disc(1.0, 2.0, 0.1));
  auto t0 = std::chrono::steady_clock::now();
  EXPECT_TRUE(first_disc_overlap(pile, {}).has_value());
  for (BodyDef& d : pile) d.type = BodyType::static_body;
  pile[777] = disc(50.0, 50.0, 0.1);
  EXPECT_EQ(first_disc_overlap(pile, {}), std::nullopt);
  // A square lattice of touching discs: no overlap, few neighbours in each window.
  std::vector<BodyDef> lattice;
  for (int i = 0; i < 200000; ++i) lattice.push_back(disc(0.2 * (i % 447), 0.2 * (i / 447), 0.1));
  EXPECT_EQ(first_disc_overlap(lattice, {}), std::nullopt);
  EXPECT_LT(seconds_since(t0), 20.0);  // ~0.1 s optimised; sanitizer builds are slower
}

// --- the scene loader ---

TEST(SceneOverlap, DiscsOverlappingAtTheStartAreALocatedErrorNamingBoth) {
  const std::string text = R"([world]
dt = 0.01
[contacts]
[[body]]
name = "left"
mass = 1
position = [0, 0]
radius = 1
[[body]]
name = "right"
mass = 1
position = [1.5, 0]
radius = 1
)";
  try {
    (void)parse_scene(text, "o.toml");
    FAIL() << "accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.line(), 9u) << e.what();
    EXPECT_EQ(e.key(), "body[1]") << e.what();
    EXPECT_NE(std::string(e.what()).find(
                  "discs \"left\" (line 4) and \"right\" (line 9) overlap by 0.5 m where they "
                  "start (centres 1.5 m apart, radii 1 + 1 m)"),
              std::string::npos)
        << e.what();
  }
  // Without [contacts], linked, not colliding, or both static: no error.
  auto replaced = [&](std::string_view from, std::string_view to) {
    std::string out = text;
    for (std::size_t at = out.find(from); at != std::string::npos; at = out.find(from, at)) {
      out.replace(at, from.size(), to);
      at += to.size();
    }
    return out;
  };
  EXPECT_NO_THROW((void)parse_scene(replaced("[contacts]\n", ""), "o.toml"));
  EXPECT_NO_THROW((void)parse_scene(
      text + "[[spring]]\nbodies = [\"left\", \"right\"]\nstiffness = 1\n", "o.toml"));
  EXPECT_NO_THROW((void)parse_scene(text + "collide = false\n", "o.toml"));
  EXPECT_NO_THROW((void)parse_scene(replaced("mass = 1\n", "type = \"static\"\n"), "o.toml"));
}

TEST(SceneOverlap, GeneratedDiscsAreNamedWithTheirGeneratorsKey) {
  try {
    (void)parse_scene(R"([world]
dt = 0.01
[contacts]
[[body]]
name = "ball"
mass = 1
position = [50, 0]
radius = 1
[[grid]]
name = "pit"
columns = 3
rows = 2
origin = [0, 0]
spacing = [0.15, 0.3]
body = { mass = 0.1, radius = 0.1 }
)",
                      "g.toml");
    FAIL() << "accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.line(), 9u) << e.what();
    EXPECT_EQ(e.key(), "grid[0]") << e.what();
    EXPECT_NE(std::string(e.what()).find("discs \"pit[0,0]\" (line 9) and \"pit[1,0]\" (line 9) "
                                         "overlap by 0.05 m"),
              std::string::npos)
        << e.what();
  }
}

TEST(SceneOverlap, AGridWithoutSpringsIsABallPitAndStaticPegsAGaltonBoard) {
  const Scene s = parse_scene(R"([world]
dt = 0.005
[contacts]
restitution = 0.3
friction = 0.2
[[grid]]
name = "ball"
columns = 40
rows = 25
origin = [-3.9, 2.0]
spacing = [0.2, 0.2]
body = { mass = 0.01, gravity = [0, -9.81], radius = 0.1, restitution = 0.5, friction = 0.4 }
[[grid]]
name = "peg"
columns = 10
rows = 5
origin = [-4.5, -1.0]
spacing = [1.0, -0.5]
body = { type = "static", radius = 0.05, collide = true }
link = { stiffness = 10 }
[[chain]]
name = "row"
count = 5
start = [10, 0]
spacing = [0.2, 0]
body = { mass = 1, radius = 0.1 }
)",
                              "pit.toml");
  ASSERT_EQ(s.def.bodies.size(), 1000u + 50u + 5u);
  EXPECT_TRUE(s.def.links.empty());           // no spring tables, and none between static pegs
  EXPECT_EQ(s.def.bodies[0].name, "row[0]");  // chains come before grids
  EXPECT_EQ(s.def.bodies[5].name, "ball[0,0]");
  EXPECT_EQ(s.def.bodies[5].type, BodyType::dynamic);
  EXPECT_EQ(s.def.bodies[5].collider->restitution, std::optional<double>(0.5));
  EXPECT_EQ(s.def.bodies[5].collider->friction, std::optional<double>(0.4));
  EXPECT_TRUE(s.def.bodies[5].gravity.has_value());
  const BodyDef& peg = s.def.bodies[1005];
  EXPECT_EQ(peg.name, "peg[0,0]");
  EXPECT_EQ(peg.type, BodyType::static_body);
  EXPECT_EQ(peg.collider->radius, 0.05);
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("pit.toml:20:8: grid[1].link: ignored: the bodies are static "
                               "(body.type), and a spring between two static bodies or pinning "
                               "one moves nothing"),
            std::string::npos)
      << s.warnings[0];
}

TEST(SceneOverlap, APileOfDiscsAtOnePointIsRefusedInBoundedTime) {
  // 2·10^5 discs here (the million of docs/BAD_INPUTS.md, made by `fixstep run`, take 2.1-2.4 s).
  const auto t0 = std::chrono::steady_clock::now();
  try {
    (void)parse_scene(R"([world]
dt = 0.01
[contacts]
[[grid]]
columns = 1000
rows = 200
origin = [0, 0]
spacing = [0, 0]
body = { mass = 1, radius = 0.5 }
)",
                      "pile.toml");
    FAIL() << "accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key(), "grid[0]") << e.what();
    EXPECT_NE(std::string(e.what()).find("overlap by 1 m"), std::string::npos) << e.what();
  }
  EXPECT_LT(seconds_since(t0), 30.0);  // most of it making the bodies
}

}  // namespace
}  // namespace fixstep
