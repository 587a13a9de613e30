#include "determinism_cases.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>

#include "fixstep/core/defined_bodies.hpp"
#include "fixstep/core/definition_checks.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_settings.hpp"

namespace fixstep::determinism {

std::filesystem::path scenes_dir() {
  return FIXSTEP_SOURCE_DIR "/assets/scenes";
}

std::filesystem::path golden_file() {
  return FIXSTEP_SOURCE_DIR "/tests/golden/state_hashes.txt";
}

std::string Case::key() const {
  return fmt::format("{} {} {}", scene, integrator_name(integrator), precision_name(precision));
}

Scene scene_for(const Case& c) {
  Scene s = load_scene(scenes_dir() / c.scene);
  s.def.settings.integrator = c.integrator;
  s.def.precision = c.precision;
  return s;
}

namespace {

/// Implicit Euler on a scene with more links than this is left out of the cases: each of its
/// steps runs Newton's method with a sparse LU factorization per iteration (world_implicit.cpp),
/// about 7 ms per tick for cloth.toml's 400 bodies in the ci build and a second per tick (and
/// 60 ms for soft_body.toml's 49) in the Debug ASan build, where 1000 ticks would take the
/// suite's time many times over. rope.toml (39 links) and chain.toml keep the implicit network
/// path in the golden hashes.
constexpr std::size_t max_links_for_implicit = 40;

}  // namespace

/// Scenes whose ticks cost far more than the others' are stepped for a fraction of each test's
/// tick count here (every case still runs, with contacts under way): ball_pit.toml steps 1008
/// discs in contact, about 1.5 ms a tick in the ci build (1000 ticks of its 12 cases would add
/// 20 s per test, minutes under ASan), galton_board.toml 240 discs among 321 static ones,
/// about 0.3 ms. The golden hashes of ball_pit.toml are after 250 ticks (1.25 s: the first
/// balls reach the floor), those of galton_board.toml after 500 (1 s: the funnel is filling).
std::uint64_t ticks_for(const std::string& scene, std::uint64_t ticks) {
  if (scene == "ball_pit.toml") return ticks / 4;
  if (scene == "galton_board.toml") return ticks / 2;
  return ticks;
}

std::vector<Case> all_cases() {
  std::vector<std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(scenes_dir())) {
    if (e.path().extension() == ".toml") files.push_back(e.path().filename().string());
  }
  std::sort(files.begin(), files.end());
  std::vector<Case> cases;
  for (const std::string& f : files) {
    for (Integrator i : all_integrators) {
      for (Precision p : {Precision::f64, Precision::f32}) {
        const Case c{f, i, p};
        try {
          const Scene scene = scene_for(c);
          if (i == Integrator::implicit_euler && scene.def.links.size() > max_links_for_implicit) {
            continue;
          }
          (void)World(scene.def);
        } catch (const UnstableDefinition&) {
          continue;  // refused by the stability guard: nothing to step
        }
        cases.push_back(c);
      }
    }
  }
  return cases;
}

std::uint64_t hash_direct(const Case& c, std::uint64_t ticks) {
  World sim = World(scene_for(c).def);
  ticks = ticks_for(c.scene, ticks);
  for (std::uint64_t t = 0; t < ticks; ++t) sim.step();
  return sim.state_hash();
}

std::map<std::string, std::string> read_golden() {
  std::map<std::string, std::string> golden;
  std::ifstream in(golden_file());
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const auto cut = line.rfind(' ');
    golden[line.substr(0, cut)] = line.substr(cut + 1);
  }
  return golden;
}

TickInput scripted_input(std::uint64_t t) {
  TickInput in;
  in.tick = t;
  if (t % 50 < 10) in.push = {0.5, -0.25};
  if (t % 70 >= 30 && t % 70 < 45)
    in.drag_body = fixstep::defined_entity(0), in.pointer = {0.3, 0.2};
  return in;
}

}  // namespace fixstep::determinism
