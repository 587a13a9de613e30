// The consumer: assets/scenes/default.toml's world built in code with fixstep::core (and io's
// summary line),
// stepped 1000 ticks. It prints the summary line `fixstep run assets/scenes/default.toml
// --steps 1000` prints, digit for digit (state hash, energy, dissipated energy, balance;
// checked by check.sh in .ci/run): a world written in code is the scene's world.
#include <cstdio>
#include <exception>
#include <fixstep/core/components.hpp>
#include <fixstep/core/step_results.hpp>
#include <fixstep/core/world.hpp>
#include <fixstep/core/world_def.hpp>
#include <fixstep/core/world_settings.hpp>
#include <fixstep/io/summary.hpp>

namespace {

fixstep::BodyDef anchored(const char* name, fixstep::Vec2 position, fixstep::SpringDamper spring,
                          fixstep::Vec2 gravity = {}) {
  fixstep::BodyDef d;
  d.name = name;
  d.body = {.mass = 1.0, .position = position, .velocity = {}};
  d.spring = spring;
  if (gravity.y != 0.0) d.gravity = fixstep::Gravity{gravity};
  return d;
}

fixstep::BodyDef thrown(const char* name, double mass, fixstep::Vec2 velocity, double drag) {
  fixstep::BodyDef d;
  d.name = name;
  d.body = {.mass = mass, .position = {-38.0, -14.0}, .velocity = velocity};
  d.gravity = fixstep::Gravity{{0.0, -9.81}};          // m/s²
  if (drag > 0.0) d.drag = fixstep::LinearDrag{drag};  // N·s/m
  return d;
}

}  // namespace

int main() {
  using namespace fixstep;
  try {
    WorldDef def;
    def.settings = {.dt = 0.01, .integrator = Integrator::semi_implicit_euler};
    def.settings.track_dissipation = true;  // as scenes do: dissipated energy is accounted
    // Springs: anchor (m), stiffness k (N/m), damping b (N·s/m), rest length (m).
    def.bodies = {
        anchored("bob", {-5, 16}, {.anchor = {-20, 16}, .stiffness = 15, .damping = 0.1}),
        anchored("elastic_pendulum", {18, 18},
                 {.anchor = {8, 26}, .stiffness = 20, .damping = 0.05, .rest_length = 8},
                 {0, -9.81}),
        anchored("damped", {30, 2}, {.anchor = {30, 14}, .stiffness = 60, .damping = 2}),
        thrown("ball", 1.0, {14, 18}, 0.0),
        thrown("feather", 0.1, {14, 18}, 0.1),
        thrown("cannonball", 5.0, {22, 14}, 0.2),
    };
    World sim = World(def);
    const double e0 = sim.energy().total();  // J
    for (int tick = 0; tick < 1000; ++tick) sim.step();
    std::printf("%s\n", summary_line(sim, e0).c_str());  // the line `fixstep run` ends with
  } catch (const std::exception& e) {
    std::fprintf(stderr, "consumer: %s\n", e.what());
    return 1;
  }
  return 0;
}
