// The scenes of bench_coupled and their energy (see coupled.hpp for the physics).
#include <cmath>
#include <numbers>

#include "coupled.hpp"

namespace coupled {

using fixstep::Body;
using fixstep::BodyDef;
using BodyLink = fixstep::IndexLink;
using fixstep::LinkSpring;
using fixstep::SpringDamper;

double Peer::dissipated() const {
  return std::nan("");
}

const char* scene_name(SceneKind s) {
  return s == SceneKind::chain ? "chain" : "cloth";
}

Scene make_chain(std::size_t n) {
  Scene s{.kind = SceneKind::chain};
  const double stretch = chain_pull / chain_stiffness;  // m per spring
  const double two_pi = 2.0 * std::numbers::pi;
  for (std::size_t j = 0; j < n; ++j) {
    BodyDef d;
    const double i = double(j + 1);
    d.body.mass = chain_mass;
    d.body.position = {stretch * i, 0.0};
    d.body.velocity = {0.5 * std::sin(two_pi * i / 16.0) + 0.25 * std::sin(two_pi * i / 4.0), 0.0};
    if (j == 0) {
      d.spring = SpringDamper{.anchor = {}, .stiffness = chain_stiffness, .damping = chain_damping};
    }
    if (j + 1 == n) d.constant_force = fixstep::ConstantForce{{chain_pull, 0.0}};
    s.bodies.push_back(d);
    s.rest_shift.push_back({i, 0.0});
  }
  for (std::size_t j = 0; j + 1 < n; ++j) {
    s.links.push_back(
        {j, j + 1, LinkSpring{.stiffness = chain_stiffness, .damping = chain_damping}});
  }
  return s;
}

Scene make_cloth(std::size_t side) {
  Scene s{.kind = SceneKind::cloth};
  const double two_pi = 2.0 * std::numbers::pi;
  auto at = [side](std::size_t r, std::size_t c) { return r * side + c; };
  for (std::size_t r = 0; r < side; ++r) {
    for (std::size_t c = 0; c < side; ++c) {
      BodyDef d;
      d.body.mass = chain_mass;
      d.body.position = {cloth_spacing * double(c), -cloth_spacing * double(r)};
      const double pc = two_pi * double(c + 1) / 16.0, pr = two_pi * double(r + 1) / 16.0;
      d.body.velocity = {0.3 * std::sin(pc) * std::cos(pr), 0.3 * std::cos(pc) * std::sin(pr)};
      s.bodies.push_back(d);
    }
  }
  const LinkSpring spring{.stiffness = chain_stiffness, .damping = chain_damping};
  for (std::size_t r = 0; r < side; ++r) {
    for (std::size_t c = 0; c < side; ++c) {
      if (c + 1 < side) s.links.push_back({at(r, c), at(r, c + 1), spring});
      if (r + 1 < side) s.links.push_back({at(r, c), at(r + 1, c), spring});
    }
  }
  // The frame: each border body's anchor sits where its spring balances the links' pull on
  // the grid, so the grid is the equilibrium and no link shortens towards zero length.
  std::vector<fixstep::Vec2> pull(s.bodies.size());
  for (const BodyLink& l : s.links) {
    const auto& a = s.bodies[l.body_a].body.position;
    const auto& b = s.bodies[l.body_b].body.position;
    const double fx = -l.spring.stiffness * (a.x - b.x), fy = -l.spring.stiffness * (a.y - b.y);
    pull[l.body_a].x += fx, pull[l.body_a].y += fy;
    pull[l.body_b].x -= fx, pull[l.body_b].y -= fy;
  }
  for (std::size_t r = 0; r < side; ++r) {
    for (std::size_t c = 0; c < side; ++c) {
      if (r != 0 && c != 0 && r + 1 != side && c + 1 != side) continue;
      BodyDef& d = s.bodies[at(r, c)];
      const fixstep::Vec2 p = d.body.position, f = pull[at(r, c)];
      d.spring = SpringDamper{.anchor = {p.x + f.x / chain_stiffness, p.y + f.y / chain_stiffness},
                              .stiffness = chain_stiffness,
                              .damping = chain_damping};
    }
  }
  return s;
}

Scene make_scene(SceneKind kind, std::size_t bodies) {
  if (kind == SceneKind::chain) return make_chain(bodies);
  return make_cloth(static_cast<std::size_t>(std::llround(std::sqrt(double(bodies)))));
}

double energy(const Scene& s, std::span<const Body> state) {
  double e = 0.0;
  for (std::size_t j = 0; j < s.bodies.size(); ++j) {
    const Body& b = state[j];
    const BodyDef& d = s.bodies[j];
    e += 0.5 * d.body.mass * (b.velocity.x * b.velocity.x + b.velocity.y * b.velocity.y);
    if (d.spring) {
      const double dx = b.position.x - d.spring->anchor.x, dy = b.position.y - d.spring->anchor.y;
      e += 0.5 * d.spring->stiffness * (dx * dx + dy * dy);
    }
    if (d.constant_force) {
      e -= d.constant_force->force.x * b.position.x + d.constant_force->force.y * b.position.y;
    }
  }
  for (const BodyLink& l : s.links) {
    const Body &a = state[l.body_a], &b = state[l.body_b];
    const double dx = a.position.x - b.position.x, dy = a.position.y - b.position.y;
    e += 0.5 * l.spring.stiffness * (dx * dx + dy * dy);
  }
  return e;
}

double equilibrium_energy(const Scene& s) {
  std::vector<Body> rest;
  for (const BodyDef& d : s.bodies) rest.push_back({d.body.mass, d.body.position, {}});
  return energy(s, rest);
}

}  // namespace coupled
