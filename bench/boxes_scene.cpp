// bench_boxes' scenes (one generator for every engine) and the overlap measured on every
// engine's poses the same way: box-box by the separating axis theorem over a uniform grid,
// box-ground and box-wall by the deepest vertex.
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

#include "boxes.hpp"

namespace boxes {

const char* box_scene_name(BoxSceneKind k) {
  if (k == BoxSceneKind::tower) return "tower";
  return k == BoxSceneKind::pyramid ? "pyramid" : "box_pile";
}

namespace {

/// SplitMix64 (Steele, Lea, Flood 2014), as bench_discs' generator: the same numbers on every
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

/// The box's four corners, counter-clockwise.
std::array<Vec2, 4> corners(const Pose& p) {
  const double c = std::cos(p.angle), s = std::sin(p.angle);
  const Vec2 u{half * c, half * s}, v{-half * s, half * c};  // the half-axes
  const Vec2 x = p.position;
  return {{{x.x - u.x - v.x, x.y - u.y - v.y},
           {x.x + u.x - v.x, x.y + u.y - v.y},
           {x.x + u.x + v.x, x.y + u.y + v.y},
           {x.x - u.x + v.x, x.y - u.y + v.y}}};
}

/// Two boxes' centres farther apart than this never overlap (twice the half-diagonal).
constexpr double reach = 2.0 * half * 1.4142135623730951;

}  // namespace

BoxScene make_pyramid(int rows) {
  BoxScene s{.kind = BoxSceneKind::pyramid, .warmup = pyramid_warmup};
  const double a = half;
  for (int i = 0; i < rows; ++i) {
    for (int j = i; j < rows; ++j) {
      s.start.push_back({{(i + 1) * a + 2.0 * (j - i) * a - a * rows, (2 * i + 1) * a}, 0.0});
    }
  }
  return s;
}

BoxScene make_tower(int boxes) {
  BoxScene s{.kind = BoxSceneKind::tower, .warmup = pyramid_warmup};
  for (int i = 0; i < boxes; ++i) s.start.push_back({{0.0, (2 * i + 1) * half}, 0.0});
  return s;
}

BoxScene make_box_pile(std::size_t n, std::uint64_t seed) {
  if (n == 0) throw std::invalid_argument("make_box_pile: no boxes");
  const auto columns = std::size_t(std::ceil(2.0 * std::sqrt(double(n))));
  const std::size_t rows = (n + columns - 1) / columns;
  BoxScene s{.kind = BoxSceneKind::box_pile,
             .width = double(columns) * pile_spacing,
             .wall_height = double(rows + 1) * pile_spacing,
             .warmup = pile_warmup};
  Random random(seed);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t row = k / columns, column = k % columns;
    s.start.push_back({{(double(column) + 0.5) * pile_spacing, 1.0 + double(row) * pile_spacing},
                       random.uniform(-pile_max_tilt, pile_max_tilt)});
  }
  return s;
}

BoxScene make_box_scene(BoxSceneKind k, std::size_t n) {
  if (k == BoxSceneKind::tower) return make_tower();
  return k == BoxSceneKind::pyramid ? make_pyramid() : make_box_pile(n);
}

double box_penetration(const Pose& a, const Pose& b) {
  const Vec2 d{b.position.x - a.position.x, b.position.y - a.position.y};
  if (d.x * d.x + d.y * d.y >= reach * reach) return 0.0;
  const double ca = std::cos(a.angle), sa = std::sin(a.angle);
  const double cb = std::cos(b.angle), sb = std::sin(b.angle);
  const std::array<Vec2, 4> axes{{{ca, sa}, {-sa, ca}, {cb, sb}, {-sb, cb}}};
  double depth = INFINITY;
  for (const Vec2& n : axes) {
    // Each box's projected half-width on n: half (|u·n| + |v·n|) with u, v its unit axes.
    const double ra = half * (std::abs(ca * n.x + sa * n.y) + std::abs(-sa * n.x + ca * n.y));
    const double rb = half * (std::abs(cb * n.x + sb * n.y) + std::abs(-sb * n.x + cb * n.y));
    const double overlap = ra + rb - std::abs(d.x * n.x + d.y * n.y);
    if (overlap <= 0.0) return 0.0;
    depth = std::min(depth, overlap);
  }
  return depth;
}

BoxQuality measure_boxes(const BoxScene& s, std::span<const Pose> poses) {
  BoxQuality q;
  // Static geometry: the ground y = 0 and, for a container, the walls' inner faces.
  for (const Pose& p : poses) {
    for (const Vec2& c : corners(p)) {
      q.static_overlap = std::max(q.static_overlap, -c.y);
      if (s.width > 0.0) q.static_overlap = std::max({q.static_overlap, -c.x, c.x - s.width});
    }
  }
  // Box-box: a grid of cell `reach` (so every overlapping pair is in neighbouring cells), each
  // pair tested once (from the box of lower index).
  const auto cell = [](double v) { return std::int64_t(std::floor(v / reach)); };
  const auto key = [](std::int64_t i, std::int64_t j) {
    return (std::uint64_t(i) << 32) ^ std::uint64_t(std::uint32_t(j));
  };
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> grid;
  grid.reserve(poses.size());
  for (std::size_t k = 0; k < poses.size(); ++k) {
    grid[key(cell(poses[k].position.x), cell(poses[k].position.y))].push_back(k);
  }
  for (std::size_t k = 0; k < poses.size(); ++k) {
    const std::int64_t ci = cell(poses[k].position.x), cj = cell(poses[k].position.y);
    for (std::int64_t di = -1; di <= 1; ++di) {
      for (std::int64_t dj = -1; dj <= 1; ++dj) {
        const auto it = grid.find(key(ci + di, cj + dj));
        if (it == grid.end()) continue;
        for (std::size_t m : it->second) {
          if (m > k) q.box_overlap = std::max(q.box_overlap, box_penetration(poses[k], poses[m]));
        }
      }
    }
  }
  if (s.kind != BoxSceneKind::box_pile) {  // the pyramid's or the tower's top box
    if (!poses.empty()) q.height = s.start.back().position.y - poses.back().position.y;
  } else {
    double sum = 0.0;
    for (const Pose& p : poses) sum += p.position.y;
    q.height = poses.empty() ? 0.0 : sum / double(poses.size());
  }
  return q;
}

double box_overlap_brute_force(std::span<const Pose> poses) {
  double deepest = 0.0;
  for (std::size_t k = 0; k < poses.size(); ++k) {
    for (std::size_t m = k + 1; m < poses.size(); ++m) {
      deepest = std::max(deepest, box_penetration(poses[k], poses[m]));
    }
  }
  return deepest;
}

}  // namespace boxes
