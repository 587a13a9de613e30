// bench_discs' scenes (one generator for every engine) and the measures taken on every engine's
// state the same way: deepest overlaps by a uniform grid, kinetic energy.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>

#include "discs.hpp"

namespace discs {

using fixstep::Vec2;

const char* scene_name(SceneKind s) {
  switch (s) {
    case SceneKind::pile:
      return "pile";
    case SceneKind::gas:
      return "gas";
    case SceneKind::pile_large:
      return "pile_large";
    case SceneKind::pile_settled:
      return "pile_settled";
    case SceneKind::pile_ball:
      break;
  }
  return "pile_ball";
}

namespace {

/// SplitMix64 (Steele, Lea, Flood 2014): the same numbers on every standard library, unlike
/// the <random> distributions.
class Random {
 public:
  explicit Random(std::uint64_t seed) : state_(seed) {}
  double uniform(double lo, double hi) {  // [lo, hi)
    return lo + (hi - lo) * double(next() >> 11) * 0x1.0p-53;
  }

 private:
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  std::uint64_t state_;
};

constexpr double gap = 1e-6;  // the lattices' gaps, as a fraction of the diameter

}  // namespace

Scene make_pile(std::size_t n, double radius) {
  // Even rows hold `wide` discs wall to wall, odd rows one fewer in the pockets between them:
  // the one hexagonal packing a box holds without holes at the rows' ends (a row with a hole
  // spreads under the rows above, and the lattice collapses).
  const std::size_t wide = (n + pile_layers / 2 + pile_layers - 1) / pile_layers;
  const double s = 2.0 * radius * (1.0 + gap);     // spacing within a row
  const double h = std::numbers::sqrt3 / 2.0 * s;  // between rows
  Scene sc{.kind = radius == small_radius ? SceneKind::pile : SceneKind::pile_large,
           .radius = radius,
           .gravity = pile_gravity,
           .restitution = pile_restitution,
           .friction = pile_friction,
           .warmup = pile_warmup};
  sc.width = double(wide) * s;
  for (std::size_t row = 0; sc.position.size() < n; ++row) {
    const bool odd = row % 2 == 1;
    for (std::size_t i = 0; i < (odd ? wide - 1 : wide) && sc.position.size() < n; ++i) {
      sc.position.push_back({(odd ? s : s / 2.0) + double(i) * s, s / 2.0 + double(row) * h});
      sc.velocity.push_back({});
    }
  }
  sc.height = 2.0 * (sc.position.back().y + radius);
  return sc;
}

Scene make_gas(std::size_t n, std::uint64_t seed) {
  const double radius = small_radius;
  Scene sc{.kind = SceneKind::gas,
           .lid = true,
           .restitution = gas_restitution,
           .friction = gas_friction,
           .warmup = gas_warmup};
  const double side = std::sqrt(double(n) * std::numbers::pi * radius * radius / gas_area_fraction);
  const auto cells = std::size_t(std::ceil(std::sqrt(double(n))));
  const double cell = side / double(cells);
  const double room = cell / 2.0 - radius * (1.0 + gap);  // centre's freedom within its cell
  if (room <= 0.0) throw std::invalid_argument("gas: the cells are narrower than a disc");
  sc.width = sc.height = side;
  Random rng(seed);
  for (std::size_t j = 0; j < n; ++j) {
    const double cx = (double(j % cells) + 0.5) * cell, cy = (double(j / cells) + 0.5) * cell;
    sc.position.push_back({cx + rng.uniform(-room, room), cy + rng.uniform(-room, room)});
    const double speed = rng.uniform(gas_speed_min, gas_speed_max);
    const double angle = rng.uniform(0.0, 2.0 * std::numbers::pi);
    sc.velocity.push_back({speed * std::cos(angle), speed * std::sin(angle)});
  }
  return sc;
}

Scene make_scene(SceneKind kind, std::size_t n) {
  if (kind == SceneKind::gas) return make_gas(n);
  if (kind == SceneKind::pile_settled || kind == SceneKind::pile_ball) {
    Scene sc = make_pile(n, small_radius);
    sc.kind = kind;
    sc.warmup = pile_settled_warmup;
    if (kind == SceneKind::pile_ball) {  // one disc more: n + 1 bodies
      sc.position.push_back({sc.width / 4.0, sc.position.back().y + ball_height});
      sc.velocity.push_back({ball_speed, 0.0});
      sc.ball = true;
    }
    return sc;
  }
  return make_pile(n, kind == SceneKind::pile ? small_radius : large_radius);
}

double initial_kinetic(const Scene& s) {
  double e = 0.0;
  for (const Vec2& v : s.velocity) e += 0.5 * mass * (v.x * v.x + v.y * v.y);
  return e;
}

namespace {

/// The grid cell of a point, packed into one key (cells of side 2r).
std::int64_t cell_key(Vec2 p, double radius) {
  const auto clamp = [](double c) { return std::clamp(c, -1e9, 1e9); };
  const auto cx = std::int64_t(std::floor(clamp(p.x / (2.0 * radius))));
  const auto cy = std::int64_t(std::floor(clamp(p.y / (2.0 * radius))));
  return (cx << 32) + cy;
}

double disc_overlap(std::span<const Vec2> x, double radius) {
  std::vector<std::pair<std::int64_t, std::uint32_t>> sorted(x.size());
  for (std::size_t j = 0; j < x.size(); ++j) sorted[j] = {cell_key(x[j], radius), std::uint32_t(j)};
  std::sort(sorted.begin(), sorted.end());
  double deepest = 0.0;
  for (std::size_t j = 0; j < x.size(); ++j) {
    const std::int64_t key = cell_key(x[j], radius);
    for (std::int64_t dx = -1; dx <= 1; ++dx) {
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        const std::int64_t k = key + (dx << 32) + dy;
        auto it = std::lower_bound(sorted.begin(), sorted.end(), std::pair{k, std::uint32_t(0)});
        for (; it != sorted.end() && it->first == k; ++it) {
          if (it->second <= j) continue;  // each pair once
          const Vec2 q = x[it->second];
          const double d = std::hypot(x[j].x - q.x, x[j].y - q.y);
          deepest = std::max(deepest, 2.0 * radius - d);
        }
      }
    }
  }
  return deepest;
}

}  // namespace

double overlap_brute_force(std::span<const Vec2> x, double radius) {
  double deepest = 0.0;
  for (std::size_t a = 0; a < x.size(); ++a) {
    for (std::size_t b = a + 1; b < x.size(); ++b) {
      const double d = std::hypot(x[a].x - x[b].x, x[a].y - x[b].y);
      deepest = std::max(deepest, 2.0 * radius - d);
    }
  }
  return deepest;
}

Quality measure(const Scene& s, std::span<const Vec2> x, std::span<const Vec2> v) {
  Quality q;
  const double radius = s.radius;
  q.disc_overlap = disc_overlap(x, radius);
  for (const Vec2& p : x) {
    double gap_left = std::min({p.x, s.width - p.x, p.y});
    if (s.lid) gap_left = std::min(gap_left, s.height - p.y);
    q.wall_overlap = std::max(q.wall_overlap, radius - gap_left);
  }
  for (const Vec2& u : v) q.kinetic += 0.5 * mass * (u.x * u.x + u.y * u.y);
  return q;
}

}  // namespace discs
