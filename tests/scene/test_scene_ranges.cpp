// Every numeric key of a scene checked against what a step's arithmetic holds
// (value_ranges.hpp): the state keys within max_state_magnitude, divisors (mass, inertia,
// radius) at least min_coefficient, every number 0 or within [1e-100, 1e100] in magnitude,
// each refused at its file:line:column and key; and each boundary itself accepted.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

#include "fixstep/core/world.hpp"
#include "fixstep/scene/scene.hpp"

namespace fixstep {
namespace {

/// [world] (lines 1-2), [contacts] rolling (3-5), then one disc's keys from line 6 with
/// `extra` as line 11 (and on).
std::string disc_scene(std::string_view extra) {
  return "[world]\ndt = 0.01\n[contacts]\nrolling = true\nfriction = 0.5\n[[body]]\n"
         "mass = 1.0\nposition = [0.0, 0.5]\nradius = 0.5\ngravity = [0.0, -9.81]\n" +
         std::string(extra) + "\n";
}

/// The SceneError parse_scene throws for text ("" when it loads and World(def) accepts it).
std::string range_error_of(const std::string& text, std::size_t& line, std::size_t& column) {
  try {
    Scene s = parse_scene(text, "r.toml");
    s.def.allow_unstable = true;  // the ranges, not the integrator's stability, are checked
    (void)World(s.def);           // the world accepts what the loader does
  } catch (const SceneError& e) {
    line = e.line(), column = e.column();
    return e.key() + ": " + e.what();
  } catch (const std::invalid_argument& e) {
    return std::string("world: ") + e.what();
  }
  return "";
}

struct Case {
  std::string_view extra;  ///< line 11 of disc_scene
  std::string_view key;    ///< the key named ("" when the scene loads)
};

// The report's two instances, refused at load naming file:line:column and key (the old loader
// ran the first to energy=inf and turned the second's state to NaN).
TEST(SceneRanges, ASpinOf1e308AndASubnormalInertiaAreRefusedAtTheirKeys) {
  std::size_t line = 0, column = 0;
  std::string e = range_error_of(disc_scene("angular_velocity = 1e308"), line, column);
  EXPECT_EQ(line, 11u) << e;
  EXPECT_EQ(column, 20u) << e;
  EXPECT_EQ(e.rfind("body[0].angular_velocity: r.toml:11:20:", 0), 0u) << e;
  EXPECT_NE(e.find("must be within +-1e+12 rad/s"), std::string::npos) << e;
  e = range_error_of(disc_scene("inertia = 5e-324"), line, column);
  EXPECT_EQ(line, 11u) << e;
  EXPECT_EQ(e.rfind("body[0].inertia: r.toml:11:", 0), 0u) << e;
  EXPECT_NE(e.find("in [1e-100, 1e100] kg*m^2"), std::string::npos) << e;
}

// Each range's boundary loads; the next value beyond it is refused at its key.
TEST(SceneRanges, EveryBoundaryLoadsAndTheValueBeyondIsRefusedAtItsKey) {
  const Case cases[] = {
      {"angular_velocity = 1e12", ""},
      {"angular_velocity = -1.000001e12", "body[0].angular_velocity"},
      {"angle = -1e12", ""},
      {"angle = 1.000001e12", "body[0].angle"},
      {"inertia = 1e-100", ""},
      {"inertia = 9.9e-101", "body[0].inertia"},
      {"inertia = 1e100", ""},
      {"inertia = 1.1e100", "body[0].inertia"},
      {"velocity = [1e12, -1e12]", ""},
      {"velocity = [0.0, 1.1e12]", "body[0].velocity[1]"},
      {"force = [1e100, -1e100]", ""},
      {"force = [2e100, 0.0]", "body[0].force[0]"},
      {"force = [5e-324, 0.0]", "body[0].force[0]"},
      {"drag = 1e100", ""},
      {"drag = 1e101", "body[0].drag"},
      {"drag = 1e-310", "body[0].drag"},
      {"friction = 1e100", ""},
      {"friction = 1e101", "body[0].friction"},
      {"spring = { anchor = [0.0, 1e12], stiffness = 1e100, damping = 1e100 }", ""},
      {"spring = { anchor = [0.0, 1.1e12], stiffness = 1.0 }", "body[0].spring.anchor[1]"},
      {"spring = { anchor = [0.0, 0.0], stiffness = 1.1e100 }", "body[0].spring.stiffness"},
      {"spring = { anchor = [0.0, 0.0], stiffness = 1.0, rest_length = 2e12 }",
       "body[0].spring.rest_length"},
      {"spring = { anchor = [0.0, 0.0], frequency = 1e60 }", "body[0].spring.frequency"},
  };
  for (const Case& c : cases) {
    std::size_t line = 0, column = 0;
    const std::string e = range_error_of(disc_scene(c.extra), line, column);
    if (c.key.empty()) {
      EXPECT_EQ(e, "") << c.extra;
      continue;
    }
    EXPECT_EQ(line, 11u) << c.extra << ": " << e;
    EXPECT_GT(column, 0u) << c.extra << ": " << e;
    EXPECT_EQ(e.rfind(std::string(c.key) + ": r.toml:11:", 0), 0u) << c.extra << ": " << e;
  }
}

// The body's own keys on their lines: mass, position and radius (a divisor, bounded below).
TEST(SceneRanges, MassPositionRadiusAndPlaneKeysAreBounded) {
  const std::pair<std::string, std::string_view> cases[] = {
      {"[world]\ndt = 0.01\n[[body]]\nmass = 1e-100\nposition = [0.0, 0.0]\n", ""},
      {"[world]\ndt = 0.01\n[[body]]\nmass = 5e-324\nposition = [0.0, 0.0]\n", "body[0].mass"},
      {"[world]\ndt = 0.01\n[[body]]\nmass = 1e101\nposition = [0.0, 0.0]\n", "body[0].mass"},
      {"[world]\ndt = 0.01\n[[body]]\nmass = 1.0\nposition = [-1.5e12, 0.0]\n",
       "body[0].position[0]"},
      {"[world]\ndt = 0.01\n[[body]]\nmass = 1.0\nposition = [0.0, 0.0]\nradius = 1e-100\n", ""},
      {"[world]\ndt = 0.01\n[[body]]\nmass = 1.0\nposition = [0.0, 0.0]\nradius = 5e-324\n",
       "body[0].radius"},
      {"[world]\ndt = 0.01\n[[body]]\nmass = 1.0\nposition = [0.0, 2.0]\nradius = 1.0\n"
       "[[plane]]\nnormal = [0.0, 1.0]\noffset = -2e12\n",
       "plane[0].offset"},
      {"[world]\ndt = 0.01\n[[body]]\nmass = 1.0\nposition = [0.0, 2.0]\nradius = 1.0\n"
       "[[plane]]\nnormal = [0.0, 1.0]\nfriction = 1e200\n",
       "plane[0].friction"},
      {"[world]\ndt = 5e-324\n[[body]]\nmass = 1.0\nposition = [0.0, 0.0]\n", "world.dt"},
      // A generated body beyond the range is the spacing's (chain0[10] at 1e12 m is the edge).
      {"[world]\ndt = 0.01\n[[chain]]\ncount = 11\nstart = [0, 0]\nspacing = [1e11, 0]\n"
       "body = { mass = 1 }\n",
       ""},
      {"[world]\ndt = 0.01\n[[chain]]\ncount = 12\nstart = [0, 0]\nspacing = [1e11, 0]\n"
       "body = { mass = 1 }\n",
       "chain[0].spacing"},
  };
  for (const auto& [text, key] : cases) {
    std::size_t line = 0, column = 0;
    const std::string e = range_error_of(text, line, column);
    if (key.empty()) {
      EXPECT_EQ(e, "") << text;
      continue;
    }
    EXPECT_GT(line, 0u) << text << ": " << e;
    EXPECT_EQ(e.rfind(std::string(key) + ": r.toml:", 0), 0u) << text << ": " << e;
  }
}

}  // namespace
}  // namespace fixstep
