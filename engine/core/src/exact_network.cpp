// exact::LinearNetwork: the modal solution of M x'' = -K x - C x' + f for networks of bodies
// joined by zero-rest-length links, with proportional damping C = αK + βM (Géradin & Rixen,
// Mechanical Vibrations, 3rd ed., §2.5 normal modes, §2.8 proportional damping).
//
// With L = 0 every force is linear and acts on each axis alone, so x and y share one n×n
// system: K has each anchored spring's k on the diagonal and each link's k in the 2×2 pattern
// [k -k; -k k] of its ends; C is built the same way from the anchored dampers plus drag (on
// the diagonal) and the link dampers; M = diag(m); f = F + m g + k·anchor per body.
// Bodies that no link connects belong to different blocks, which never interact: each
// connected component is decomposed on its own and may have its own α and β (a scene with a
// damped chain and a few unrelated anchored bodies is still solved exactly).
#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <string>

#include "fixstep/core/components.hpp"
#include "fixstep/core/defined_bodies.hpp"
#include "fixstep/core/exact.hpp"

namespace fixstep::exact {

struct LinearNetwork::Modes {
  /// One connected component: its bodies (indices into the body list), the mass-normalised
  /// modes (columns of phi, φᵀMφ = 1) and, per mode, ω² (1/s²), γ (1/s), the initial modal
  /// coordinates q = φᵀ M x and q' per axis (kg^½·m, kg^½·m/s) and the modal force φᵀ f
  /// (kg^½·m/s²).
  struct Block {
    std::vector<std::size_t> bodies;
    Eigen::MatrixXd phi;
    std::vector<double> omega2, gamma, qx, vx, qy, vy, fx, fy;
    /// Decomposes this component, of bodies `all[bodies[j]]` joined by `links` (local[i]: body
    /// i's place in it); false when its damping is not proportional.
    bool decompose(std::span<const BodyDef> all, std::span<const fixstep::IndexLink* const> links,
                   const std::vector<std::size_t>& local);
  };
  std::vector<double> mass;
  std::vector<Block> blocks;
};

namespace {

[[noreturn]] void fail(const std::string& what) {
  throw std::invalid_argument("fixstep::exact::LinearNetwork: " + what);
}

void check_body(const BodyDef& def, std::size_t i) {
  const std::string who = fmt::format("body[{}] '{}'", i, def.name);
  auto finite = [&](double v, const char* name) {
    if (!std::isfinite(v)) fail(fmt::format("{}: {} must be finite (got {})", who, name, v));
  };
  auto rate = [&](double v, const char* name) {
    if (!(std::isfinite(v) && v >= 0.0)) {
      fail(fmt::format("{}: {} must be finite and >= 0 (got {})", who, name, v));
    }
  };
  const Body& b = def.body;
  if (!(std::isfinite(b.mass) && b.mass > 0.0)) {
    fail(fmt::format("{}: mass must be finite and > 0 (got {})", who, b.mass));
  }
  finite(b.position.x, "position.x"), finite(b.position.y, "position.y");
  finite(b.velocity.x, "velocity.x"), finite(b.velocity.y, "velocity.y");
  if (def.spring) {
    finite(def.spring->anchor.x, "anchor.x"), finite(def.spring->anchor.y, "anchor.y");
    rate(def.spring->stiffness, "stiffness"), rate(def.spring->damping, "damping");
    rate(def.spring->rest_length, "rest_length");
  }
  if (def.constant_force) {
    finite(def.constant_force->force.x, "force.x"), finite(def.constant_force->force.y, "force.y");
  }
  if (def.gravity) {
    finite(def.gravity->acceleration.x, "gravity.x");
    finite(def.gravity->acceleration.y, "gravity.y");
  }
  if (def.drag) rate(def.drag->coefficient, "drag coefficient");
}

void check_link(const fixstep::IndexLink& l, std::size_t i) {
  if (l.body_a == l.body_b) fail(fmt::format("link[{}]: both ends are body {}", i, l.body_a));
  for (auto [v, name] :
       {std::pair{l.spring.stiffness, "stiffness"}, std::pair{l.spring.damping, "damping"},
        std::pair{l.spring.rest_length, "rest_length"}}) {
    if (!(std::isfinite(v) && v >= 0.0)) {
      fail(fmt::format("link[{}]: {} must be finite and >= 0 (got {})", i, name, v));
    }
  }
}

/// Finds α, β with C = αK + βM for one component, or returns false. The unknowns appear in one
/// equation per damper: a link's b = α k, a body's b + c = α k_anchor + β m (0 where it has
/// none). Least squares over these rows (columns scaled to unit size, minimum-norm solution
/// when α and β are not both determined; a coefficient contributing below 1e-12 of the largest
/// damper is set to 0), then every row must hold to a relative 1e-9 of its terms. With no
/// damping anywhere the right-hand side is 0 and so are α and β.
bool proportional(const std::vector<std::array<double, 3>>& rows) {
  const auto count = static_cast<Eigen::Index>(rows.size());
  Eigen::MatrixXd a(count, 2);
  Eigen::VectorXd d(count);
  for (Eigen::Index r = 0; r < count; ++r) {
    const auto& row = rows[static_cast<std::size_t>(r)];
    a(r, 0) = row[0], a(r, 1) = row[1], d(r) = row[2];
  }
  if (d.cwiseAbs().maxCoeff() == 0.0) return true;  // α = β = 0
  Eigen::Vector2d scale;
  for (int c = 0; c < 2; ++c) {
    const double s = a.col(c).cwiseAbs().maxCoeff();
    scale(c) = s > 0.0 ? s : 1.0;
    a.col(c) /= scale(c);
  }
  Eigen::Vector2d x = a.completeOrthogonalDecomposition().solve(d);
  // A term below 1e-12 of the largest damper is the fit's round-off (β ~ 1e-18 where no body
  // has drag): 0, so that rows whose damping is 0 can hold exactly.
  const double largest = d.cwiseAbs().maxCoeff();
  for (int c = 0; c < 2; ++c) {
    if (std::abs(x(c)) * a.col(c).cwiseAbs().maxCoeff() <= 1e-12 * largest) x(c) = 0.0;
  }
  for (Eigen::Index r = 0; r < count; ++r) {
    const double ta = a(r, 0) * x(0), tb = a(r, 1) * x(1);
    const double residual = ta + tb - d(r);
    if (std::abs(residual) > 1e-9 * (std::abs(ta) + std::abs(tb) + std::abs(d(r)))) return false;
  }
  return true;
}

std::size_t find(std::vector<std::size_t>& parent, std::size_t i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

/// The links by place, after checking every body and link (fail names the first bad one).
std::vector<fixstep::IndexLink> checked_links(std::span<const BodyDef> bodies,
                                              std::span<const LinkDef> link_defs) {
  for (std::size_t i = 0; i < bodies.size(); ++i) check_body(bodies[i], i);
  std::vector<fixstep::IndexLink> links = fixstep::index_links(link_defs, bodies.size());
  for (std::size_t l = 0; l < links.size(); ++l) check_link(links[l], l);
  return links;
}

/// Some spring or link has a rest length: the forces are not linear.
bool has_rest_length(std::span<const BodyDef> bodies, std::span<const fixstep::IndexLink> links) {
  return std::any_of(bodies.begin(), bodies.end(),
                     [](const BodyDef& b) { return b.spring && b.spring->rest_length > 0.0; }) ||
         std::any_of(links.begin(), links.end(),
                     [](const fixstep::IndexLink& l) { return l.spring.rest_length > 0.0; });
}

/// The connected components of n bodies joined by links (union-find): each component's bodies
/// in body order, each body's place in its component, each component's links in link order.
struct Components {
  std::vector<std::vector<std::size_t>> bodies;
  std::vector<std::size_t> local;
  std::vector<std::vector<const fixstep::IndexLink*>> links;
};

Components connected_components(std::size_t n, std::span<const fixstep::IndexLink> links) {
  std::vector<std::size_t> parent(n);
  std::iota(parent.begin(), parent.end(), std::size_t{0});
  for (const fixstep::IndexLink& l : links) parent[find(parent, l.body_a)] = find(parent, l.body_b);
  Components c;
  std::vector<std::size_t> block_of(n, n);
  c.local.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t root = find(parent, i);
    if (block_of[root] == n) block_of[root] = c.bodies.size(), c.bodies.emplace_back();
    c.local[i] = c.bodies[block_of[root]].size();
    c.bodies[block_of[root]].push_back(i);
  }
  c.links.resize(c.bodies.size());
  for (const fixstep::IndexLink& l : links) c.links[block_of[find(parent, l.body_a)]].push_back(&l);
  return c;
}

/// One component's K, C (n×n, shared by x and y), M, loads f = F + m g + k·anchor and initial
/// state, with one row {coefficient of α, of β, damping} per damper for proportional().
struct BlockSystem {
  Eigen::MatrixXd k, c;
  Eigen::VectorXd m, fx, fy, x0, y0, vx0, vy0;
  std::vector<std::array<double, 3>> rows;
};

BlockSystem assemble(std::span<const BodyDef> all, const std::vector<std::size_t>& members,
                     std::span<const fixstep::IndexLink* const> links,
                     const std::vector<std::size_t>& local) {
  const auto nb = static_cast<Eigen::Index>(members.size());
  BlockSystem s{
      Eigen::MatrixXd::Zero(nb, nb), Eigen::MatrixXd::Zero(nb, nb), {}, {}, {}, {}, {}, {}, {}, {}};
  for (Eigen::VectorXd* v : {&s.m, &s.fx, &s.fy, &s.x0, &s.y0, &s.vx0, &s.vy0}) v->resize(nb);
  for (Eigen::Index j = 0; j < nb; ++j) {
    const BodyDef& def = all[members[static_cast<std::size_t>(j)]];
    const double mass = def.body.mass;
    const double ka = def.spring ? def.spring->stiffness : 0.0;
    const double damp =
        (def.spring ? def.spring->damping : 0.0) + (def.drag ? def.drag->coefficient : 0.0);
    s.m(j) = mass, s.k(j, j) = ka, s.c(j, j) = damp;
    s.rows.push_back({ka, mass, damp});
    const Vec2 anchor = def.spring ? def.spring->anchor : Vec2{};
    const Vec2 force = def.constant_force ? def.constant_force->force : Vec2{};
    const Vec2 g = def.gravity ? def.gravity->acceleration : Vec2{};
    s.fx(j) = force.x + mass * g.x + ka * anchor.x;
    s.fy(j) = force.y + mass * g.y + ka * anchor.y;
    s.x0(j) = def.body.position.x, s.y0(j) = def.body.position.y;
    s.vx0(j) = def.body.velocity.x, s.vy0(j) = def.body.velocity.y;
  }
  for (const fixstep::IndexLink* l : links) {
    const auto a = static_cast<Eigen::Index>(local[l->body_a]);
    const auto b = static_cast<Eigen::Index>(local[l->body_b]);
    const double kl = l->spring.stiffness, bl = l->spring.damping;
    s.k(a, a) += kl, s.k(b, b) += kl, s.k(a, b) -= kl, s.k(b, a) -= kl;
    s.c(a, a) += bl, s.c(b, b) += bl, s.c(a, b) -= bl, s.c(b, a) -= bl;
    s.rows.push_back({kl, 0.0, bl});
  }
  return s;
}

}  // namespace

bool LinearNetwork::Modes::Block::decompose(std::span<const BodyDef> all,
                                            std::span<const fixstep::IndexLink* const> links,
                                            const std::vector<std::size_t>& local) {
  const BlockSystem s = assemble(all, bodies, links, local);
  if (!proportional(s.rows)) return false;
  const auto nb = static_cast<Eigen::Index>(bodies.size());
  // K φ = ω² M φ with φᵀMφ = 1 (Eigen reduces it with the Cholesky factor of M, here
  // M^½, to the symmetric M^-½ K M^-½).
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(
      s.k, Eigen::MatrixXd(s.m.asDiagonal()), Eigen::ComputeEigenvectors | Eigen::Ax_lBx);
  if (solver.info() != Eigen::Success) {
    throw std::runtime_error("fixstep::exact::LinearNetwork: eigen-decomposition failed");
  }
  phi = solver.eigenvectors();
  const Eigen::VectorXd& w2 = solver.eigenvalues();
  // K is positive semidefinite: eigenvalues below the round-off of the largest (a few ulps
  // times the size) are the rigid motions of a free component, exactly 0.
  const double top = w2.cwiseAbs().maxCoeff();
  const double zero = 64.0 * static_cast<double>(nb) * std::numeric_limits<double>::epsilon() * top;
  const Eigen::MatrixXd mphi = s.m.asDiagonal() * phi;
  const Eigen::VectorXd q_x = mphi.transpose() * s.x0, q_y = mphi.transpose() * s.y0;
  const Eigen::VectorXd v_x = mphi.transpose() * s.vx0, v_y = mphi.transpose() * s.vy0;
  const Eigen::VectorXd p_x = phi.transpose() * s.fx, p_y = phi.transpose() * s.fy;
  for (Eigen::Index j = 0; j < nb; ++j) {
    omega2.push_back(w2(j) > zero ? w2(j) : 0.0);
    // γ = φᵀCφ, which is α ω² + β for C = αK + βM, without the fit's round-off.
    gamma.push_back(std::max(0.0, phi.col(j).dot(s.c * phi.col(j))));
    qx.push_back(q_x(j)), qy.push_back(q_y(j));
    vx.push_back(v_x(j)), vy.push_back(v_y(j));
    fx.push_back(p_x(j)), fy.push_back(p_y(j));
  }
  return true;
}

std::optional<LinearNetwork> LinearNetwork::make(std::span<const BodyDef> bodies,
                                                 std::span<const LinkDef> link_defs) {
  const std::vector<fixstep::IndexLink> links = checked_links(bodies, link_defs);
  if (has_rest_length(bodies, links)) return std::nullopt;  // nonlinear
  const Components components = connected_components(bodies.size(), links);
  auto modes = std::make_unique<Modes>();
  for (const BodyDef& b : bodies) modes->mass.push_back(b.body.mass);
  modes->blocks.resize(components.bodies.size());
  for (std::size_t bi = 0; bi < modes->blocks.size(); ++bi) {
    Modes::Block& blk = modes->blocks[bi];
    blk.bodies = components.bodies[bi];
    if (!blk.decompose(bodies, components.links[bi], components.local)) return std::nullopt;
  }
  return LinearNetwork(std::move(modes));
}

void LinearNetwork::state(double t, std::span<Body> out) const {
  if (out.size() != modes_->mass.size()) {
    fail(fmt::format("state: out holds {} bodies, the network has {}", out.size(),
                     modes_->mass.size()));
  }
  if (!std::isfinite(t)) fail(fmt::format("state: t must be finite (got {})", t));
  for (const Modes::Block& blk : modes_->blocks) {
    const auto nb = static_cast<Eigen::Index>(blk.bodies.size());
    Eigen::VectorXd q(nb), dq(nb), r(nb), dr(nb);
    for (Eigen::Index j = 0; j < nb; ++j) {
      const auto u = static_cast<std::size_t>(j);
      const AxisState sx =
          linear(blk.qx[u], blk.vx[u], blk.omega2[u], blk.gamma[u], 0.0, blk.fx[u], t);
      const AxisState sy =
          linear(blk.qy[u], blk.vy[u], blk.omega2[u], blk.gamma[u], 0.0, blk.fy[u], t);
      q(j) = sx.x, dq(j) = sx.v, r(j) = sy.x, dr(j) = sy.v;
    }
    const Eigen::VectorXd x = blk.phi * q, vx = blk.phi * dq, y = blk.phi * r, vy = blk.phi * dr;
    for (Eigen::Index j = 0; j < nb; ++j) {
      Body& b = out[blk.bodies[static_cast<std::size_t>(j)]];
      b.mass = modes_->mass[blk.bodies[static_cast<std::size_t>(j)]];
      b.position = {x(j), y(j)};
      b.velocity = {vx(j), vy(j)};
    }
  }
}

std::size_t LinearNetwork::size() const {
  return modes_->mass.size();
}

LinearNetwork::LinearNetwork(std::unique_ptr<Modes> modes) : modes_(std::move(modes)) {}
LinearNetwork::LinearNetwork(LinearNetwork&&) noexcept = default;
LinearNetwork& LinearNetwork::operator=(LinearNetwork&&) noexcept = default;
LinearNetwork::~LinearNetwork() = default;

}  // namespace fixstep::exact
