// The joints' direct solve (joint_tree.hpp): the forest, its order and its block LDLᵀ.
#include "joint_tree.hpp"

#include <algorithm>
#include <numeric>

#include "copy_bytes.hpp"
#include "shape_world.hpp"

namespace fixstep::detail {

namespace {

using Block = std::array<double, 9>;
using Vec3 = std::array<double, 3>;

/// The inverse of a 3×3 block by its cofactors (zero when singular).
Block inverse3(const Block& k) {
  const double c0 = k[4] * k[8] - k[5] * k[7], c3 = k[5] * k[6] - k[3] * k[8],
               c6 = k[3] * k[7] - k[4] * k[6];
  double det = k[0] * c0 + k[1] * c3 + k[2] * c6;
  if (det == 0.0) return {};
  det = 1.0 / det;
  return {det * c0, det * (k[2] * k[7] - k[1] * k[8]), det * (k[1] * k[5] - k[2] * k[4]),
          det * c3, det * (k[0] * k[8] - k[2] * k[6]), det * (k[2] * k[3] - k[0] * k[5]),
          det * c6, det * (k[1] * k[6] - k[0] * k[7]), det * (k[0] * k[4] - k[1] * k[3])};
}

bool moves(std::uint32_t body, std::span<const ShapedBody> bodies) {
  return body != JointRecord::none &&
         (bodies[body].inv_mass > 0.0 || bodies[body].inv_inertia > 0.0);
}

/// A body that turns but does not translate: a point on it moves along one line only.
bool turns_only(std::uint32_t body, std::span<const ShapedBody> bodies) {
  return body != JointRecord::none && bodies[body].inv_mass == 0.0 &&
         bodies[body].inv_inertia > 0.0;
}

}  // namespace

std::uint32_t JointTree::find(std::uint32_t k) {
  while (root_[k] != k) {
    root_[k] = root_[root_[k]];  // path halving
    k = root_[k];
  }
  return k;
}

void JointTree::build(std::span<JointRecord> joints, std::span<const std::uint32_t> listed,
                      std::span<const ShapedBody> bodies, const JointBodies& numbered) {
  members_.clear(), ends_.clear();
  if (listed.empty()) {  // no forest, and no pass over the bodies
    bodies_.clear(), ordered_ends_.clear();
    all_members_.clear(), arms_.clear(), rhs_.clear(), angle_rows_.clear(), angle_rhs_.clear();
    return;
  }
  const auto ground = static_cast<std::uint32_t>(numbered.size());
  root_.resize(numbered.size() + 1);
  std::iota(root_.begin(), root_.end(), 0U);
  for (const std::uint32_t i : listed) {
    JointRecord& j = joints[i];
    j.direct = false;
    if (j.def.type != JointType::revolute || j.broken) continue;
    if (turns_only(j.a, bodies) || turns_only(j.b, bodies)) continue;
    const std::uint32_t a = moves(j.a, bodies) ? j.a : none;
    const std::uint32_t b = moves(j.b, bodies) ? j.b : none;
    if (a == none && b == none) continue;
    const std::uint32_t ra = find(a == none ? ground : numbered.local(a));
    const std::uint32_t rb = find(b == none ? ground : numbered.local(b));
    if (ra == rb) continue;  // it would close a loop
    root_[ra] = rb;
    j.direct = true;
    members_.push_back(i);
    ends_.push_back({a, b});
  }
  all_members_.resize(members_.size());
  std::iota(all_members_.begin(), all_members_.end(), 0U);
  arms_.resize(members_.size());
  rhs_.resize(members_.size());
  angle_rows_.assign(members_.size(), 0);
  angle_rhs_.resize(members_.size());
  if (members_.empty()) {
    bodies_.clear(), ordered_ends_.clear();
  } else if (ends_ == ordered_ends_) {
    reweigh(bodies);
  } else {
    order(bodies, numbered);
    ordered_ends_ = ends_;
  }
}

// The nodes order() made from the same ends: the same, but for the bodies' masses now.
void JointTree::reweigh(std::span<const ShapedBody> bodies) {
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    const std::uint32_t body = nodes_[i].body;
    if (body == none) continue;
    inverse_mass_[i] = {bodies[body].inv_mass, bodies[body].inv_mass, bodies[body].inv_inertia};
  }
}

void JointTree::add_node(std::uint32_t parent, std::uint32_t member, std::uint32_t body,
                         std::span<const ShapedBody> bodies, const JointBodies& numbered) {
  const auto k = static_cast<std::uint32_t>(nodes_.size());
  nodes_.push_back({parent, member, body});
  tree_of_node_.push_back(parent == none ? trees_++ : tree_of_node_[parent]);
  if (body != none) {
    node_of_body_[numbered.local(body)] = k;
    bodies_.push_back(body);
    inverse_mass_.push_back(
        {bodies[body].inv_mass, bodies[body].inv_mass, bodies[body].inv_inertia});
  } else {
    node_of_member_[member] = k;
    inverse_mass_.push_back({});
  }
  stack_.push_back(k);
}

// Depth first from the node on the stack: a joint's other body, a body's other joints.
void JointTree::visit(std::span<const ShapedBody> bodies, const JointBodies& numbered) {
  while (!stack_.empty()) {
    const std::uint32_t n = stack_.back();
    stack_.pop_back();
    const Node node = nodes_[n];
    if (node.member != none) {
      for (const std::uint32_t body : ends_[node.member]) {
        if (body != none && node_of_body_[numbered.local(body)] == none) {
          add_node(n, none, body, bodies, numbered);
        }
      }
      continue;
    }
    const std::uint32_t at = numbered.local(node.body);
    for (std::uint32_t e = first_[at]; e < first_[at + 1]; ++e) {
      if (node_of_member_[joined_[e]] == none) add_node(n, joined_[e], none, bodies, numbered);
    }
  }
}

// Each tree from its joint to the ground where it has one (a joint must not be a leaf: its
// pivot would be zero), else from its first joint's first moving body.
void JointTree::order(std::span<const ShapedBody> bodies, const JointBodies& numbered) {
  first_.assign(numbered.size() + 1, 0);
  for (const auto& e : ends_) {
    for (const std::uint32_t body : e) {
      if (body != none) ++first_[numbered.local(body) + 1];
    }
  }
  std::partial_sum(first_.begin(), first_.end(), first_.begin());
  joined_.resize(first_.back());
  stack_.assign(first_.begin(), first_.end() - 1);  // (each body's next free place)
  for (std::uint32_t m = 0; m < ends_.size(); ++m) {
    for (const std::uint32_t body : ends_[m]) {
      if (body != none) joined_[stack_[numbered.local(body)]++] = m;
    }
  }
  stack_.clear();
  nodes_.clear(), inverse_mass_.clear(), bodies_.clear(), tree_of_node_.clear();
  trees_ = 0;
  node_of_body_.assign(numbered.size(), none);
  node_of_member_.assign(members_.size(), none);
  for (std::uint32_t m = 0; m < ends_.size(); ++m) {
    if (ends_[m][0] != none && ends_[m][1] != none) continue;
    add_node(none, m, none, bodies, numbered);
    visit(bodies, numbered);
  }
  for (std::uint32_t m = 0; m < ends_.size(); ++m) {
    if (node_of_member_[m] != none) continue;
    add_node(none, none, ends_[m][0], bodies, numbered);
    visit(bodies, numbered);
  }
  const std::size_t n = nodes_.size();
  inverse_.resize(n), up_.resize(n), pivot_.resize(n), x_.resize(n);
  all_nodes_.resize(n);
  std::iota(all_nodes_.begin(), all_nodes_.end(), 0U);
  tree_of_member_.resize(members_.size());
  for (std::size_t m = 0; m < members_.size(); ++m) {
    tree_of_member_[m] = tree_of_node_[node_of_member_[m]];
  }
  make_runs(whole);
}

void JointTree::split(std::span<const std::uint8_t> half_of_body, const JointBodies& numbered) {
  for (int h = 0; h < 2; ++h) part_nodes_[h].clear(), part_members_[h].clear();
  for (int h = 0; h < 2; ++h) part_bodies_[h].clear();
  auto half_of_member = [&](std::uint32_t m) {
    return half_of_body[numbered.local(ends_[m][0] != none ? ends_[m][0] : ends_[m][1])];
  };
  for (std::uint32_t i = 0; i < nodes_.size(); ++i) {
    const Node& node = nodes_[i];
    const std::uint8_t h =
        node.body != none ? half_of_body[numbered.local(node.body)] : half_of_member(node.member);
    part_nodes_[h].push_back(i);
    if (node.body != none) part_bodies_[h].push_back(node.body);
  }
  for (std::uint32_t m = 0; m < members_.size(); ++m) part_members_[half_of_member(m)].push_back(m);
  make_runs(0), make_runs(1);
}

void JointTree::make_runs(int part) {
  std::vector<Run>& runs = runs_[static_cast<std::size_t>(part)];
  runs.clear();
  const auto nodes = nodes_of(part);
  for (std::uint32_t at = 0; at < nodes.size(); ++at) {
    const std::uint32_t tree = tree_of_node_[nodes[at]];
    if (runs.empty() || runs.back().tree != tree) runs.push_back({tree, at, 0});
    ++runs.back().count;
  }
}

// A node's link to its parent: the point row's Jacobian on the body's end, Ċ = v_b + ω_b × r_b
// − v_a − ω_a × r_a, so ∂Ċ/∂(v, ω) = s [[1, 0, u_x], [0, 1, u_y]] with s = ±1 (B's end, A's)
// and u = (−r_y, r_x), zero for a body that does not turn.
[[gnu::always_inline]] inline JointTree::Link JointTree::link(std::size_t i) const {
  const Node& node = nodes_[i];
  const bool joint = node.member != none;
  const std::uint32_t member = joint ? node.member : nodes_[node.parent].member;
  const std::uint32_t body = joint ? nodes_[node.parent].body : node.body;
  const int side = ends_[member][0] == body ? 0 : 1;
  const Vec2 r = arms_[member][side];
  const bool turns = inverse_mass_[joint ? node.parent : i][2] > 0.0;
  const bool angle = factored_angles_[member] != 0;
  return {side == 0 ? -1.0 : 1.0, turns ? Vec2{-r.y, r.x} : Vec2{}, angle && turns ? 1.0 : 0.0,
          angle};
}

// A joint node into its parent body: D⁻¹ J (its rows, 3×3), and the body's pivot less
// Jᵀ D⁻¹ J. `angle`: l.angle, as a constant (the loops without its tests).
template <bool angle>
[[gnu::always_inline]] inline void JointTree::eliminate_joint(std::size_t i, const Link& l) {
  const double s = l.s, t = l.t;
  const Vec2 u = l.u;
  const Block& d = inverse_[i];
  Block& up = up_[i];
  Block& p = pivot_[nodes_[i].parent];
  const std::size_t rows = angle ? 3 : 2;
  for (std::size_t r = 0; r < rows; ++r) {
    up[3 * r] = s * d[3 * r], up[3 * r + 1] = s * d[3 * r + 1];
    up[3 * r + 2] = angle ? s * (d[3 * r] * u.x + d[3 * r + 1] * u.y + d[3 * r + 2] * t)
                          : s * (d[3 * r] * u.x + d[3 * r + 1] * u.y);
  }
  if (!angle) up[6] = up[7] = up[8] = 0.0;
  for (std::size_t c = 0; c < 3; ++c) {
    p[c] -= s * up[c], p[3 + c] -= s * up[3 + c];
    p[6 + c] -= angle ? s * (u.x * up[c] + u.y * up[3 + c] + t * up[6 + c])
                      : s * (u.x * up[c] + u.y * up[3 + c]);
  }
}

// A body node into its parent joint: D⁻¹ Jᵀ (3×2, or 3×3 with the joint's angle row), and
// the joint's pivot less J D⁻¹ Jᵀ. `angle`: l.angle, as a constant.
template <bool angle>
[[gnu::always_inline]] inline void JointTree::eliminate_body(std::size_t i, const Link& l) {
  const double s = l.s, t = l.t;
  const Vec2 u = l.u;
  const Block& d = inverse_[i];
  Block& up = up_[i];
  Block& p = pivot_[nodes_[i].parent];
  for (std::size_t r = 0; r < 3; ++r) {
    up[3 * r] = s * (d[3 * r] + u.x * d[3 * r + 2]);
    up[3 * r + 1] = s * (d[3 * r + 1] + u.y * d[3 * r + 2]);
    up[3 * r + 2] = angle ? s * (t * d[3 * r + 2]) : 0.0;
  }
  const std::size_t columns = angle ? 3 : 2;
  for (std::size_t c = 0; c < columns; ++c) {
    p[c] -= s * (up[c] + u.x * up[6 + c]);
    p[3 + c] -= s * (up[3 + c] + u.y * up[6 + c]);
    if (angle) p[6 + c] -= s * (t * up[6 + c]);
  }
}

// Block LDLᵀ from the leaves: a node's pivot D is its H block less its children's D⁻¹ H
// products; up_ holds D⁻¹ H of a node and its parent. A joint's pivot is 2×2 (its third row
// and column void: 1 on the diagonal), or 3×3 with an angle row; a body's 3×3.
void JointTree::factor() {
  factor_angles();
  factor_part(whole);
}

void JointTree::factor_angles() {
  factored_angles_.assign(angle_rows_.begin(), angle_rows_.end());
  for (std::size_t i = 0; i < nodes_.size(); ++i) {  // (see angle_rows())
    const std::uint32_t p = nodes_[i].parent;
    if (nodes_[i].member == none && p != none && inverse_mass_[i][2] == 0.0) {
      factored_angles_[nodes_[p].member] = 0;
    }
  }
  any_angle_ =
      std::find(factored_angles_.begin(), factored_angles_.end(), 1) != factored_angles_.end();
}

void JointTree::factor_part(int part) {
  const auto nodes = nodes_of(part);
  for (const std::uint32_t i : nodes) {
    if (nodes_[i].member != none) {
      const double void_row = factored_angles_[nodes_[i].member] != 0 ? 0.0 : 1.0;
      pivot_[i] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, void_row};
      continue;
    }
    const Vec3& w = inverse_mass_[i];
    const double m = 1.0 / w[0], inertia = w[2] > 0.0 ? 1.0 / w[2] : 1.0;
    pivot_[i] = {m, 0.0, 0.0, 0.0, m, 0.0, 0.0, 0.0, inertia};
  }
  for (std::size_t at = nodes.size(); at-- > 0;) {  // children before parents
    const std::uint32_t i = nodes[at];
    const Node& node = nodes_[i];
    const Block& k = pivot_[i];
    Block& d = inverse_[i];
    if (node.member != none && factored_angles_[node.member] == 0) {
      const double det = k[0] * k[4] - k[1] * k[3];
      const double inv = det != 0.0 ? 1.0 / det : 0.0;
      d = {inv * k[4], -inv * k[1], 0.0, -inv * k[3], inv * k[0], 0.0, 0.0, 0.0, 0.0};
    } else {
      d = inverse3(k);
    }
    if (node.parent == none) continue;
    const Link l = link(i);
    if (node.member != none) {
      l.angle ? eliminate_joint<true>(i, l) : eliminate_joint<false>(i, l);
    } else {
      l.angle ? eliminate_body<true>(i, l) : eliminate_body<false>(i, l);
    }
  }
}

void JointTree::solve(std::span<Vec2> rhs, std::span<double> angle_rhs, int part) {
  solve_nodes(rhs, angle_rhs, nodes_of(part));
}

void JointTree::solve(std::span<Vec2> rhs, std::span<double> angle_rhs, int part,
                      std::span<const std::uint8_t> active) {
  if (std::find(active.begin(), active.end(), 0) == active.end()) {  // every tree: no list
    solve_nodes(rhs, angle_rhs, nodes_of(part));
    return;
  }
  // The active trees' runs, those next to one another in one solve (the trees are
  // independent: each node's arithmetic is the same however they are grouped).
  const auto nodes = nodes_of(part);
  std::size_t begin = 0, end = 0;
  for (const Run& r : runs_[static_cast<std::size_t>(part)]) {
    if (active[r.tree] == 0) continue;
    if (r.first != end) {
      if (end > begin) solve_nodes(rhs, angle_rhs, nodes.subspan(begin, end - begin));
      begin = r.first;
    }
    end = std::size_t{r.first} + r.count;
  }
  if (end > begin) solve_nodes(rhs, angle_rhs, nodes.subspan(begin, end - begin));
}

void JointTree::solve_nodes(std::span<Vec2> rhs, std::span<double> angle_rhs,
                            std::span<const std::uint32_t> nodes) {
  if (any_angle_) {
    solve_with<true>(rhs, angle_rhs, nodes);
  } else {
    solve_with<false>(rhs, angle_rhs, nodes);
  }
}

// Angles: whether some member has an angle row (without, the loops test for none).
template <bool Angles>
void JointTree::solve_with(std::span<Vec2> rhs, std::span<double> angle_rhs,
                           std::span<const std::uint32_t> nodes) {
  auto angle = [&](std::size_t node) {  // whether a joint node has an angle row
    if constexpr (Angles) {
      return nodes_[node].member != none && factored_angles_[nodes_[node].member] != 0;
    } else {
      (void)node;
      return false;
    }
  };
  for (const std::uint32_t i : nodes) {
    const std::uint32_t m = nodes_[i].member;
    x_[i] = m != none ? Vec3{-rhs[m].x, -rhs[m].y, angle(i) ? -angle_rhs[m] : 0.0} : Vec3{};
  }
  for (std::size_t at = nodes.size(); at-- > 0;) {  // z_p −= (D_i⁻¹ H_ip)ᵀ z_i, children first
    const std::uint32_t i = nodes[at];
    const std::uint32_t p = nodes_[i].parent;
    if (p == none) continue;
    const Block& g = up_[i];
    const Vec3& z = x_[i];
    Vec3& zp = x_[p];
    if (nodes_[i].member == none) {  // (3×2)ᵀ, or (3×3)ᵀ below a joint's angle row
      const std::size_t columns = angle(p) ? 3 : 2;
      for (std::size_t c = 0; c < columns; ++c) {
        zp[c] -= g[c] * z[0] + g[3 + c] * z[1] + g[6 + c] * z[2];
      }
    } else if (angle(i)) {  // (3×3)ᵀ
      for (std::size_t c = 0; c < 3; ++c) zp[c] -= g[c] * z[0] + g[3 + c] * z[1] + g[6 + c] * z[2];
    } else {  // (2×3)ᵀ
      for (std::size_t c = 0; c < 3; ++c) zp[c] -= g[c] * z[0] + g[3 + c] * z[1];
    }
  }
  for (const std::uint32_t i : nodes) {  // parents first: x_i is final once made
    const std::uint32_t p = nodes_[i].parent;
    back_substitute(i, angle(i), p != none && angle(p));
    const std::uint32_t m = nodes_[i].member;
    if (m == none) continue;
    rhs[m] = {x_[i][0], x_[i][1]};
    if (Angles && angle_rows_[m] != 0) angle_rhs[m] = angle(i) ? x_[i][2] : 0.0;
  }
}

// x_i = D_i⁻¹ z_i − D_i⁻¹ H_ip x_p; `angle`: node i is a joint with an angle row;
// `parent_angle`: its parent is.
[[gnu::always_inline]] inline void JointTree::back_substitute(std::size_t i, bool angle,
                                                              bool parent_angle) {
  const Block& d = inverse_[i];
  const Block& g = up_[i];
  const std::uint32_t p = nodes_[i].parent;
  const Vec3 xp = p != none ? x_[p] : Vec3{};
  Vec3& x = x_[i];
  const Vec3 z = x;
  if (nodes_[i].member == none) {  // a 3×3 pivot, a 3×2 link (3×3 to an angle row)
    for (std::size_t r = 0; r < 3; ++r) {
      const double linked = parent_angle
                                ? g[3 * r] * xp[0] + g[3 * r + 1] * xp[1] + g[3 * r + 2] * xp[2]
                                : g[3 * r] * xp[0] + g[3 * r + 1] * xp[1];
      x[r] = d[3 * r] * z[0] + d[3 * r + 1] * z[1] + d[3 * r + 2] * z[2] - linked;
    }
  } else if (angle) {  // a 3×3 pivot, a 3×3 link
    for (std::size_t r = 0; r < 3; ++r) {
      x[r] = d[3 * r] * z[0] + d[3 * r + 1] * z[1] + d[3 * r + 2] * z[2] -
             (g[3 * r] * xp[0] + g[3 * r + 1] * xp[1] + g[3 * r + 2] * xp[2]);
    }
  } else {  // a 2×2 pivot, a 2×3 link
    for (std::size_t r = 0; r < 2; ++r) {
      x[r] = d[3 * r] * z[0] + d[3 * r + 1] * z[1] -
             (g[3 * r] * xp[0] + g[3 * r + 1] * xp[1] + g[3 * r + 2] * xp[2]);
    }
  }
}

std::size_t JointTree::bytes() const {
  return copy_bytes(members_, bodies_, ends_, arms_, rhs_, angle_rows_, factored_angles_,
                    angle_rhs_, nodes_, inverse_mass_, inverse_, up_, pivot_, x_, root_,
                    node_of_body_, first_, joined_, node_of_member_, stack_, all_nodes_,
                    all_members_, ordered_ends_, tree_of_node_, tree_of_member_) +
         copy_bytes(part_nodes_[0], part_nodes_[1], part_members_[0], part_members_[1],
                    part_bodies_[0], part_bodies_[1], runs_[0], runs_[1], runs_[2]);
}

}  // namespace fixstep::detail
