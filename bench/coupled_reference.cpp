// The reference solution bench_coupled measures errors against: the exact modal solution of
// the linear network (exact::LinearNetwork). --verify-only checks it against an independent
// computation, fixstep's RK4 at a step 256 times finer than the game's tick (ω_max h =
// 40 rad/s · 6.5e-5 s = 0.0026).
#include <cmath>
#include <stdexcept>

#include "coupled.hpp"
#include "fixstep/core/components.hpp"
#include "fixstep/core/exact.hpp"
#include "fixstep/core/world.hpp"

namespace coupled {

Reference rk4_reference(const Scene& s, std::span<const double> times, int substeps) {
  constexpr double tick = 1.0 / 60.0;
  auto w = make_world<double>(
      s, {.dt = tick, .integrator = fixstep::Integrator::rk4, .substeps = substeps, .threads = 1});
  Reference r{.method = "fixstep RK4 at h = 1/60 s / " + std::to_string(substeps)};
  for (const double t : times) {
    const auto ticks = static_cast<std::uint64_t>(std::llround(t / tick));
    if (std::abs(double(ticks) * tick - t) > 1e-9) {
      throw std::invalid_argument("rk4_reference: times must be multiples of 1/60 s");
    }
    while (w->tick() < ticks) w->step();
    std::vector<fixstep::Body> out;
    for (std::size_t j = 0; j < w->body_count(); ++j) {
      out.push_back({s.bodies[j].body.mass, {w->x()[j], w->y()[j]}, {w->vx()[j], w->vy()[j]}});
    }
    r.states.push_back(std::move(out));
  }
  return r;
}

Reference reference(const Scene& s, std::span<const double> times) {
  auto net = fixstep::exact::LinearNetwork::make(s.bodies, link_defs(s));
  if (!net)
    throw std::invalid_argument(
        "reference: the scene is not a proportionally damped linear network");
  Reference r{.method = "exact::LinearNetwork (modal solution)"};
  for (const double t : times) {
    std::vector<fixstep::Body> out(s.bodies.size());
    net->state(t, out);
    r.states.push_back(std::move(out));
  }
  return r;
}

}  // namespace coupled
