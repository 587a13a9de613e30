// bench_joints' scenes (one generator for every engine) and what is measured on every engine's
// poses the same way: the joints' separation and limits, and the capsules' and circles'
// overlaps.
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <set>
#include <stdexcept>
#include <utility>

#include "joints.hpp"

namespace joints {

const char* joint_scene_name(JointSceneKind k) {
  if (k == JointSceneKind::chain) return "chain";
  return k == JointSceneKind::ragdoll_pile ? "ragdoll_pile" : "car";
}

namespace {

constexpr double pi = std::numbers::pi;

/// SplitMix64 (Steele, Lea, Flood 2014), as bench_boxes' generator: the same numbers on every
/// standard library.
class Random {
 public:
  explicit Random(std::uint64_t seed) : state_(seed) {}
  double uniform(double lo, double hi) {  // [lo, hi)
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    z ^= z >> 31;
    return lo + (hi - lo) * double(z >> 11) * 0x1.0p-53;
  }

 private:
  std::uint64_t state_;
};

Vec2 rotate(double angle, Vec2 v) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * v.x - s * v.y, s * v.x + c * v.y};
}
Vec2 add(Vec2 a, Vec2 b) {
  return {a.x + b.x, a.y + b.y};
}
Vec2 sub(Vec2 a, Vec2 b) {
  return {a.x - b.x, a.y - b.y};
}
/// |v| (dot and cross are fixstep's, types.hpp).
double norm(Vec2 v) {
  return std::sqrt(dot(v, v));
}

/// θ wrapped into [-π, π].
double wrap(double a) {
  return std::remainder(a, 2.0 * pi);
}

Shape capsule(Vec2 a, Vec2 b, double radius) {
  return {.kind = ShapeKind::capsule, .a = a, .b = b, .radius = radius};
}

/// One bone of Box2D's human (shared/human.c, scale 1): its body's origin, its capsule (in the
/// body frame), its parent and the hinge to it (pivot, limits in units of π), all in the
/// ragdoll's frame (feet at y ≈ 0.28 m).
struct Bone {
  Vec2 position;
  double a_y, b_y, radius;
  int parent;
  double pivot_y, lower, upper;
};
// hip, torso, head, upper/lower left leg, upper/lower right leg, upper/lower left arm, upper/lower
// right arm (Box2D's bone_ order). Two limits differ from Box2D's so that the straight start lies
// within them: the elbows' are taken about the straight arm (Box2D's human sets them about a
// reference angle of π/4), and the knees' upper limit is 0 (Box2D's −0.02π).
constexpr std::array<Bone, ragdoll_bones> human = {{
    {{0.0, 0.95}, -0.02, 0.02, 0.095, -1, 0.0, 0.0, 0.0},
    {{0.0, 1.2}, -0.135, 0.135, 0.09, 0, 1.0, -0.25, 0.0},
    {{0.0, 1.475}, -0.038, 0.039, 0.075, 1, 1.4, -0.3, 0.1},
    {{0.0, 0.775}, -0.125, 0.125, 0.06, 0, 0.9, -0.05, 0.4},
    {{0.0, 0.475}, -0.155, 0.125, 0.045, 3, 0.625, -0.5, 0.0},
    {{0.0, 0.775}, -0.125, 0.125, 0.06, 0, 0.9, -0.05, 0.4},
    {{0.0, 0.475}, -0.155, 0.125, 0.045, 5, 0.625, -0.5, 0.0},
    {{0.0, 1.225}, -0.125, 0.125, 0.035, 1, 1.35, -0.1, 0.8},
    {{0.0, 0.975}, -0.125, 0.125, 0.03, 7, 1.1, -0.2, 0.3},
    {{0.0, 1.225}, -0.125, 0.125, 0.035, 1, 1.35, -0.1, 0.8},
    {{0.0, 0.975}, -0.125, 0.125, 0.03, 9, 1.1, -0.2, 0.3},
}};
/// The ragdoll's middle (the point it is turned about and placed by), in its frame.
constexpr Vec2 ragdoll_middle{0.0, 0.93};

/// The terrain's height at x (m): flat to x = 10 m, then two rolling waves (20 m and 6.3 m
/// long, 0.5 m and 0.15 m high).
double terrain_height(double x) {
  if (x <= 10.0) return 0.0;
  const double u = x - 10.0;
  return 0.5 * std::sin(2.0 * pi * u / 20.0) + 0.15 * std::sin(2.0 * pi * u / 6.3);
}

}  // namespace

void JointScene::add_joint(JointSpec j) {
  const auto pose = [this](int i) {
    return i < 0 ? Pose{} : Pose{bodies.at(std::size_t(i)).position, bodies[std::size_t(i)].angle};
  };
  if (j.body_b < 0 || j.body_a == j.body_b) throw std::invalid_argument("add_joint: bad bodies");
  const Pose a = pose(j.body_a), b = pose(j.body_b);
  j.local_a = rotate(-a.angle, sub(j.anchor, a.position));
  j.local_b = rotate(-b.angle, sub(j.anchor, b.position));
  j.reference = b.angle - a.angle;
  const double n = norm(j.axis);
  j.axis = {j.axis.x / n, j.axis.y / n};
  j.local_axis = rotate(-a.angle, j.axis);
  joints.push_back(j);
}

JointScene make_chain(int links) {
  JointScene s{.kind = JointSceneKind::chain, .warmup = 0, .window = chain_window};
  const Shape box{.kind = ShapeKind::box, .half = {chain_half_length, chain_half_width}};
  for (int i = 0; i < links; ++i) {
    s.bodies.push_back({.position = {chain_half_length * (2 * i + 1), 0.0}, .shapes = {box}});
    s.add_joint({.body_a = i - 1, .body_b = i, .anchor = {2.0 * chain_half_length * i, 0.0}});
  }
  return s;
}

JointScene make_ragdoll_pile(int ragdolls, std::uint64_t seed) {
  if (ragdolls <= 0) throw std::invalid_argument("make_ragdoll_pile: no ragdolls");
  const int rows = (ragdolls + ragdoll_columns - 1) / ragdoll_columns;
  JointScene s{.kind = JointSceneKind::ragdoll_pile,
               .container = true,
               .width = ragdoll_columns * ragdoll_spacing,
               .wall_height = (rows + 1) * ragdoll_spacing,
               .warmup = ragdoll_warmup,
               .window = ragdoll_window};
  Random random(seed);
  for (int k = 0; k < ragdolls; ++k) {
    const Vec2 middle{(k % ragdoll_columns + 0.5) * ragdoll_spacing,
                      ragdoll_spacing * (1 + k / ragdoll_columns)};
    const double turn = random.uniform(-pi, pi);
    // A point of the ragdoll's frame, placed: turned about its middle, the middle at `middle`.
    const auto place = [&](Vec2 p) { return add(middle, rotate(turn, sub(p, ragdoll_middle))); };
    const int first = int(s.bodies.size());
    for (const Bone& bone : human) {
      s.bodies.push_back({.position = place(bone.position),
                          .angle = turn,
                          .shapes = {capsule({0.0, bone.a_y}, {0.0, bone.b_y}, bone.radius)},
                          .group = -(k + 1)});
    }
    for (int i = 0; i < ragdoll_bones; ++i) {
      const Bone& bone = human[std::size_t(i)];
      if (bone.parent < 0) continue;
      s.add_joint({.body_a = first + bone.parent,
                   .body_b = first + i,
                   .anchor = place({0.0, bone.pivot_y}),
                   .lower = bone.lower * pi,
                   .upper = bone.upper * pi});
    }
  }
  return s;
}

JointScene make_car() {
  JointScene s{.kind = JointSceneKind::car, .warmup = 0, .window = car_window};
  for (int x = -20; x <= 260; ++x) s.terrain.push_back({double(x), terrain_height(x)});
  s.bodies.push_back(
      {.position = {0.0, 1.0}, .shapes = {{.kind = ShapeKind::box, .half = {1.3, 0.3}}}});
  const Shape tyre{.kind = ShapeKind::circle,
                   .radius = 0.4,
                   .density = 2.0 * density,
                   .friction = car_tyre_friction};
  for (const double x : {-1.0, 1.0}) {
    s.bodies.push_back({.position = {x, 0.4}, .shapes = {tyre}});
    const bool rear = x < 0.0;
    s.add_joint({.kind = JointKind::wheel,
                 .body_a = 0,
                 .body_b = int(s.bodies.size()) - 1,
                 .anchor = {x, 0.4},
                 .axis = {0.0, 1.0},
                 .lower = -car_travel,
                 .upper = car_travel,
                 .frequency = car_frequency,
                 .damping_ratio = car_damping_ratio,
                 .motor_speed = rear ? car_motor_speed : 0.0,
                 .max_motor_torque = rear ? car_motor_torque : 0.0});
  }
  return s;
}

JointScene make_joint_scene(JointSceneKind k) {
  if (k == JointSceneKind::chain) return make_chain();
  return k == JointSceneKind::ragdoll_pile ? make_ragdoll_pile() : make_car();
}

JointErrors joint_errors(const JointScene& s, std::span<const Pose> poses) {
  if (poses.size() != s.bodies.size()) throw std::invalid_argument("joint_errors: pose count");
  JointErrors e;
  const auto pose = [&](int i) { return i < 0 ? Pose{} : poses[std::size_t(i)]; };
  for (const JointSpec& j : s.joints) {
    const Pose a = pose(j.body_a), b = pose(j.body_b);
    const Vec2 pa = add(a.position, rotate(a.angle, j.local_a));
    const Vec2 pb = add(b.position, rotate(b.angle, j.local_b));
    double value = 0.0;
    if (j.kind == JointKind::revolute) {
      e.separation = std::max(e.separation, norm(sub(pb, pa)));
      value = wrap(b.angle - a.angle - j.reference);
    } else {
      const Vec2 axis = rotate(a.angle, j.local_axis);
      const Vec2 d = sub(pb, pa);
      e.separation = std::max(e.separation, std::abs(cross(axis, d)));
      value = dot(axis, d);
    }
    if (j.lower) e.beyond_limit = std::max(e.beyond_limit, *j.lower - value);
    if (j.upper) e.beyond_limit = std::max(e.beyond_limit, value - *j.upper);
  }
  return e;
}

namespace {

/// A circle or capsule placed: the segment p..q swept by radius r (p = q for a circle).
struct Swept {
  Vec2 p, q;
  double r;
  int body, group;
  double lo, hi;  ///< its extent along x, m
};

/// The distance between segments p1..q1 and p2..q2 (Ericson, Real-Time Collision Detection,
/// 5.1.9, closest points of two segments).
double segment_distance(Vec2 p1, Vec2 q1, Vec2 p2, Vec2 q2) {
  const Vec2 d1 = sub(q1, p1), d2 = sub(q2, p2), r = sub(p1, p2);
  const double a = dot(d1, d1), e = dot(d2, d2), f = dot(d2, r);
  double s = 0.0, t = 0.0;
  if (a <= 1e-18 && e <= 1e-18) return norm(r);
  if (a <= 1e-18) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = dot(d1, r);
    if (e <= 1e-18) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = dot(d1, d2), denom = a * e - b * b;
      s = denom > 0.0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0.0) {
        t = 0.0, s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1.0) {
        t = 1.0, s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  const Vec2 c1{p1.x + d1.x * s, p1.y + d1.y * s}, c2{p2.x + d2.x * t, p2.y + d2.y * t};
  return norm(sub(c1, c2));
}

}  // namespace

Overlaps deepest_overlaps(const JointScene& s, std::span<const Pose> poses) {
  if (poses.size() != s.bodies.size()) throw std::invalid_argument("deepest_overlaps: poses");
  std::vector<Swept> items;
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    const Pose& x = poses[i];
    for (const Shape& sh : s.bodies[i].shapes) {
      if (sh.kind == ShapeKind::box) continue;
      const Vec2 a = sh.kind == ShapeKind::circle ? sh.center : sh.a;
      const Vec2 b = sh.kind == ShapeKind::circle ? sh.center : sh.b;
      const Vec2 p = add(x.position, rotate(x.angle, a)), q = add(x.position, rotate(x.angle, b));
      items.push_back({p, q, sh.radius, int(i), s.bodies[i].group, std::min(p.x, q.x) - sh.radius,
                       std::max(p.x, q.x) + sh.radius});
    }
  }
  std::set<std::pair<int, int>> joined;
  for (const JointSpec& j : s.joints) {
    joined.insert(std::minmax(j.body_a, j.body_b));
  }
  Overlaps o;
  for (const Swept& w : items) {
    if (s.container) {
      o.statics = std::max({o.statics, w.r - std::min(w.p.y, w.q.y), w.r - std::min(w.p.x, w.q.x),
                            std::max(w.p.x, w.q.x) + w.r - s.width});
    }
    for (std::size_t k = 1; k < s.terrain.size(); ++k) {
      const Vec2 a = s.terrain[k - 1], b = s.terrain[k];
      if (std::max(a.x, b.x) < w.lo || std::min(a.x, b.x) > w.hi) continue;
      o.statics = std::max(o.statics, w.r - segment_distance(w.p, w.q, a, b));
    }
  }
  // Pairs by a sweep along x: sorted by their left ends, each against those starting before
  // its right end.
  std::sort(items.begin(), items.end(), [](const Swept& a, const Swept& b) { return a.lo < b.lo; });
  for (std::size_t i = 0; i < items.size(); ++i) {
    const Swept& u = items[i];
    for (std::size_t k = i + 1; k < items.size() && items[k].lo <= u.hi; ++k) {
      const Swept& v = items[k];
      if (u.body == v.body || (u.group < 0 && u.group == v.group)) continue;
      if (joined.contains(std::minmax(u.body, v.body))) continue;
      o.between = std::max(o.between, u.r + v.r - segment_distance(u.p, u.q, v.p, v.q));
    }
  }
  return o;
}

}  // namespace joints
