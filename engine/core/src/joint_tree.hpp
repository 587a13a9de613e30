// The joints' direct solve: the point rows of the revolute joints that form a forest, solved
// all at once (Baraff, "Linear-Time Dynamics using Lagrange Multipliers", SIGGRAPH 1996),
// where a Gauss-Seidel sweep moves an error along a chain by one link; and, where asked, a
// member's angle row with them (a limit it is past, on positions). joint_solver.hpp's rows
// keep everything else (the limits' velocity rows, motors, springs, the other types and the
// joints that close a loop); ShapeWorld interleaves the two.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "joint_bodies.hpp"
#include "joint_record.hpp"

namespace fixstep::detail {

struct ShapedBody;

/// The forest's errors left as they are (a tree with no larger one is not solved): a
/// point's velocity error (m/s) and position error (m), each component.
inline constexpr double direct_velocity_tolerance = 1e-9;
inline constexpr double direct_position_tolerance = 1e-9;
/// The forest's Newton steps on the error a tick's motion made (the sweeps that keep, before
/// the push-out) are at most the larger of this and ContactSettings::position_iterations; they
/// end sooner once the error is within direct_position_tolerance or stops shrinking (three or
/// four steps while a chain swings). Cut to the push-out's count, a whipping 100-link chain
/// came apart with three or four.
inline constexpr int direct_position_steps = 10;

class JointTree {
 public:
  /// Which joints join the forest, in joint order: a revolute joint that is not broken, has
  /// a body that moves (a non-zero inverse mass or inertia) and none that turns without
  /// translating (its point could not follow both rows), and does not close a loop (the
  /// world, static and kinematic bodies are one node: a second joint of one tree to them
  /// closes a loop too). Of the `listed` joints only (indices into `joints`, ascending; the
  /// others keep their `direct`), whose bodies `numbered` numbers (built from the same list):
  /// O(listed joints), whatever the world holds. Sets each listed joint's `direct`; allocates
  /// only while the forest grows.
  void build(std::span<JointRecord> joints, std::span<const std::uint32_t> listed,
             std::span<const ShapedBody> bodies, const JointBodies& numbered);
  /// The joints of the forest (indices into build's span), in joint order.
  [[nodiscard]] std::span<const std::uint32_t> members() const { return members_; }
  [[nodiscard]] bool empty() const { return members_.empty(); }
  /// Whether the body numbered `local` (build's JointBodies numbering) is one of the forest's.
  [[nodiscard]] bool holds(std::uint32_t local) const {
    return local < node_of_body_.size() && node_of_body_[local] != none;
  }
  /// Heap bytes a copy holds (World::snapshot_bytes).
  [[nodiscard]] std::size_t bytes() const;

  /// Each member's lever arms (m, world frame, from A's and B's centre of mass) for the next
  /// factor(), by member index.
  [[nodiscard]] std::span<std::array<Vec2, 2>> arms() { return arms_; }
  /// A buffer of one Vec2 per member for solve()'s right-hand side.
  [[nodiscard]] std::span<Vec2> rhs() { return rhs_; }
  /// Whether each member has a third row for the next factor(), by member index: its
  /// relative angle θ_B − θ_A (0 after build(): none has). A row whose end away from the
  /// tree's root does not turn is left out (its pivot would be singular): solve() gives it 0.
  [[nodiscard]] std::span<std::uint8_t> angle_rows() { return angle_rows_; }
  /// A buffer of one value per member for solve()'s angle rows (those without one: unread).
  [[nodiscard]] std::span<double> angle_rhs() { return angle_rhs_; }
  /// Whether member k's angle row is in the last factor() (asked for, and not left out).
  [[nodiscard]] bool angle_row_kept(std::size_t k) const { return factored_angles_[k] != 0; }
  /// Factors H = [M Jᵀ; J 0] of the forest, J the point rows' Jacobian at arms() and the
  /// angle rows' (block LDLᵀ, children before parents: no fill, O(members)). A singular pivot
  /// is taken as zero (that part moves nothing). The same as factor_angles() then
  /// factor_part(whole).
  void factor();
  /// Solves K λ = rhs for the members of `part` at once (every member: whole), K = J M⁻¹ Jᵀ of
  /// the last factor: `rhs` (a velocity, m/s, or a position error, m, per member; with angle
  /// rows, `angle_rhs`: rad/s or rad) in, λ (N·s, or kg·m; N·m·s or kg·m²) out, the other
  /// part's members' entries untouched. `angle_rhs` (one per member) is needed only when the
  /// last factor had angle rows.
  void solve(std::span<Vec2> rhs, std::span<double> angle_rhs = {}, int part = whole);
  /// solve() for the trees of `part` whose entry of `active` (one per tree: tree_of()) is not
  /// 0; the other trees' members' entries untouched. The trees are independent, so each
  /// solved member gets the same bits as from solve().
  void solve(std::span<Vec2> rhs, std::span<double> angle_rhs, int part,
             std::span<const std::uint8_t> active);
  /// The forest's trees: how many, and member k's (0 ... trees() − 1, by the last build()).
  [[nodiscard]] std::size_t trees() const { return trees_; }
  [[nodiscard]] std::uint32_t tree_of(std::size_t member) const { return tree_of_member_[member]; }

  /// The forest by halves (joint_halves.hpp): part 0 and 1 are the trees whose bodies are in
  /// that half; `whole` is every tree. The trees are independent, so factoring or solving
  /// each part gives every member the same bits as the whole forest at once.
  static constexpr int whole = 2;
  /// Splits the trees by `half_of_body` (0 or 1 for each of the forest's bodies, by its number
  /// in `numbered`, build's; every body of a tree in the same half). Until the next build(),
  /// parts 0 and 1 are those trees.
  void split(std::span<const std::uint8_t> half_of_body, const JointBodies& numbered);
  /// A part's members (member indices, ascending) and bodies (indices into build's span, each
  /// once, in the forest's order).
  [[nodiscard]] std::span<const std::uint32_t> members_of(int part) const {
    return part == whole ? std::span<const std::uint32_t>(all_members_) : part_members_[part];
  }
  [[nodiscard]] std::span<const std::uint32_t> bodies_of(int part) const {
    return part == whole ? std::span<const std::uint32_t>(bodies_) : part_bodies_[part];
  }
  /// factor() in two steps: which members' angle rows are factored (every member's, on one
  /// thread), then each part's blocks (each part on its own thread, after the first step).
  void factor_angles();
  void factor_part(int part);

 private:
  using Block = std::array<double, 9>;  ///< 3×3, row-major
  using Vec3 = std::array<double, 3>;
  static constexpr std::uint32_t none = ~std::uint32_t{0};
  struct Node {
    std::uint32_t parent = none;
    std::uint32_t member = none;  ///< a joint's member index; none for a body
    std::uint32_t body = none;    ///< a body's index; none for a joint
  };
  std::vector<std::uint32_t> members_, bodies_;
  std::vector<std::array<std::uint32_t, 2>> ends_;  ///< each member's bodies (none: ground)
  /// The ends the nodes were last ordered from: order() depends on nothing else but the
  /// bodies' masses, so a build() finding the same ends keeps its nodes (reweigh()).
  std::vector<std::array<std::uint32_t, 2>> ordered_ends_;
  std::vector<std::array<Vec2, 2>> arms_;
  std::vector<Vec2> rhs_;
  std::vector<std::uint8_t> angle_rows_, factored_angles_;  ///< factored_: factor()'s
  std::vector<double> angle_rhs_;
  bool any_angle_ = false;          ///< some member of the last factor() has an angle row
  std::vector<Node> nodes_;         ///< in preorder: a parent before its children
  std::vector<Vec3> inverse_mass_;  ///< each node's body's (1/kg, 1/kg, 1/(kg·m²))
  std::vector<Block> inverse_;      ///< D⁻¹ of each node
  std::vector<Block> up_;           ///< D⁻¹ H (the node's row, its parent's column)
  std::vector<Block> pivot_;        ///< factor's scratch: D
  std::vector<Vec3> x_;             ///< solve's scratch
  // By a body's number (JointBodies): the union-find (ground last), its node, its members.
  std::vector<std::uint32_t> root_;
  std::vector<std::uint32_t> node_of_body_;
  std::vector<std::uint32_t> first_, joined_;  ///< each body's members (CSR)
  std::vector<std::uint32_t> node_of_member_, stack_;
  // Each node's and member's tree (a tree's nodes are one run of the preorder, and so of a
  // part's nodes), and each part's runs (0, 1, whole): a tree and where its nodes are in
  // nodes_of(part), for solve() with `active`.
  std::vector<std::uint32_t> tree_of_node_, tree_of_member_;
  std::uint32_t trees_ = 0;
  struct Run {
    std::uint32_t tree, first, count;
  };
  std::array<std::vector<Run>, 3> runs_;
  void make_runs(int part);
  std::vector<std::uint32_t> all_nodes_, all_members_;  ///< 0, 1, 2, ...: the whole forest
  std::array<std::vector<std::uint32_t>, 2> part_nodes_, part_members_, part_bodies_;
  [[nodiscard]] std::span<const std::uint32_t> nodes_of(int part) const {
    return part == whole ? std::span<const std::uint32_t>(all_nodes_) : part_nodes_[part];
  }

  std::uint32_t find(std::uint32_t k);
  void order(std::span<const ShapedBody> bodies, const JointBodies& numbered);
  void reweigh(std::span<const ShapedBody> bodies);
  void add_node(std::uint32_t parent, std::uint32_t member, std::uint32_t body,
                std::span<const ShapedBody> bodies, const JointBodies& numbered);
  void visit(std::span<const ShapedBody> bodies, const JointBodies& numbered);
  struct Link {
    double s = 1.0;  ///< +1 on B's end, −1 on A's
    Vec2 u{};        ///< (−r_y, r_x), zero for a body that does not turn
    /// The angle row's ∂/∂ω over s: 1 for a member with one (factored_angles_) on a body that
    /// turns, else 0 (and the member's third row void).
    double t = 0.0;
    bool angle = false;  ///< the member has an angle row
  };
  [[nodiscard]] Link link(std::size_t node) const;
  template <bool angle>
  void eliminate_joint(std::size_t node, const Link& link);
  template <bool angle>
  void eliminate_body(std::size_t node, const Link& link);
  void solve_nodes(std::span<Vec2> rhs, std::span<double> angle_rhs,
                   std::span<const std::uint32_t> nodes);
  template <bool Angles>
  void solve_with(std::span<Vec2> rhs, std::span<double> angle_rhs,
                  std::span<const std::uint32_t> nodes);
  void back_substitute(std::size_t node, bool angle, bool parent_angle);
};

}  // namespace fixstep::detail
