// The smallest fixstep program: a world made in code, stepped at a fixed dt, its bodies'
// positions printed. fixstep::core alone: no renderer, no window, no file.
#include <cstdio>
#include <fixstep/core.hpp>  // all of fixstep::core

int main() {
  using namespace fixstep;
  WorldDef def;
  def.settings.dt = 1.0 / 60.0;  // s per tick; semi-implicit Euler by default
  BodyDef ball;
  ball.name = "ball";
  ball.body = {.mass = 1.0, .position = {0.0, 10.0}, .velocity = {2.0, 0.0}};  // kg, m, m/s
  ball.gravity = Gravity{};                                                    // 9.81 m/s² down
  def.bodies.push_back(ball);
  World world(def);
  for (int tick = 1; tick <= 60; ++tick) {
    world.step();
    if (tick % 20 != 0) continue;
    for (const Entity e : world.bodies()) {
      const Vec2 p = world.body(e).position;
      std::printf("t=%.3f s %s x=%.3f m y=%.3f m\n", world.time(), world.name(e).c_str(), p.x, p.y);
    }
  }
}
