// Overlapping discs at the start (disc_overlap.hpp): sweep and prune along x, the open discs
// ordered by y.
#include "fixstep/core/disc_overlap.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <set>
#include <stdexcept>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/defined_bodies.hpp"
#include "fixstep/core/det_math.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"

namespace fixstep {

namespace {

/// A disc in the sweep: its centre and radius (m), its body index, and the ends of its
/// x-interval widened by the rounding of x ± r, so that pruning never drops a pair whose
/// exact distance test would find an overlap.
struct Disc {
  double x, y, r, left, right;
  std::size_t body;
  bool dynamic;
};

/// A bound on the rounding error of a ± b: a few ulps of |a| + |b|.
double slack(double a, double b) {
  return 4.0 * std::numeric_limits<double>::epsilon() * (std::abs(a) + std::abs(b));
}

std::vector<Disc> discs_of(std::span<const BodyDef> bodies) {
  std::vector<Disc> discs;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const BodyDef& d = bodies[i];
    if (!d.collider || !d.collider->collide || d.collider->sensor) continue;  // sensors may
    const double x = d.body.position.x, y = d.body.position.y, r = d.collider->radius;
    if (!std::isfinite(x) || !std::isfinite(y)) {
      throw std::invalid_argument(fmt::format(
          "disc overlap: body[{}] '{}': position must be finite (got ({}, {}))", i, d.name, x, y));
    }
    if (!(std::isfinite(r) && r > 0.0)) {
      throw std::invalid_argument(fmt::format(
          "disc overlap: body[{}] '{}': radius must be finite and > 0 m (got {})", i, d.name, r));
    }
    const double e = slack(x, r);
    discs.push_back(Disc{x, y, r, x - r - e, x + r + e, i, d.type == BodyType::dynamic});
  }
  return discs;
}

/// How far discs that touch may seem to overlap, m: 1e-9 of their radii plus the rounding of
/// their coordinates, so that discs placed at r_a + r_b (a row of touching balls at
/// start + i * spacing) are not taken for overlapping.
double touching_tolerance(const Disc& a, const Disc& b) {
  const double coordinate = std::max({std::abs(a.x), std::abs(a.y), std::abs(b.x), std::abs(b.y)});
  return 1e-9 * (a.r + b.r) + 4.0 * std::numeric_limits<double>::epsilon() * coordinate;
}

/// The links between two discs, as sorted (lower, higher) body index pairs.
std::vector<std::pair<std::size_t, std::size_t>> linked_pairs(std::span<const BodyDef> bodies,
                                                              std::span<const LinkDef> links) {
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  auto disc = [&](std::size_t i) { return bodies[i].collider && bodies[i].collider->collide; };
  for (const fixstep::IndexLink& link : fixstep::index_links(links, bodies.size())) {
    if (disc(link.body_a) && disc(link.body_b)) {
      pairs.emplace_back(std::min(link.body_a, link.body_b), std::max(link.body_a, link.body_b));
    }
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

/// The open discs of one side (dynamic, or static and kinematic), by (y, index into the
/// sweep's discs), and the largest radius that side has.
struct Side {
  std::set<std::pair<double, std::uint32_t>> open;
  double r_max = 0.0;
};

}  // namespace

bool discs_may_touch(const BodyDef& a, const BodyDef& b) {
  return a.collider && b.collider && a.collider->collide && b.collider->collide &&
         !a.collider->sensor && !b.collider->sensor &&
         should_collide(a.collider->filter, b.collider->filter) &&
         (a.type == BodyType::dynamic || b.type == BodyType::dynamic);
}

double disc_overlap_depth(const BodyDef& a, const BodyDef& b) {
  const double dx = a.body.position.x - b.body.position.x;
  const double dy = a.body.position.y - b.body.position.y;
  return a.collider->radius + b.collider->radius - det::hypot(dx, dy);
}

std::optional<std::pair<std::size_t, std::size_t>> first_disc_overlap(
    std::span<const BodyDef> bodies, std::span<const LinkDef> links) {
  std::vector<Disc> discs = discs_of(bodies);
  const auto linked = linked_pairs(bodies, links);
  if (discs.size() > std::numeric_limits<std::uint32_t>::max()) {
    throw std::invalid_argument("disc overlap: more than 2^32 - 1 discs");
  }
  if (std::none_of(discs.begin(), discs.end(), [](const Disc& d) { return d.dynamic; })) {
    return std::nullopt;  // no pair may touch
  }
  std::sort(discs.begin(), discs.end(), [](const Disc& a, const Disc& b) {
    return a.left != b.left ? a.left < b.left : a.body < b.body;
  });
  std::vector<std::uint32_t> by_right(discs.size());  // closing order
  for (std::uint32_t i = 0; i < by_right.size(); ++i) by_right[i] = i;
  std::sort(by_right.begin(), by_right.end(), [&](std::uint32_t a, std::uint32_t b) {
    return discs[a].right != discs[b].right ? discs[a].right < discs[b].right : a < b;
  });
  Side sides[2];  // [0] static and kinematic, [1] dynamic
  for (const Disc& d : discs) {
    Side& s = sides[d.dynamic ? 1 : 0];
    s.r_max = std::max(s.r_max, d.r);
  }
  auto overlap = [&](const Disc& a, const Disc& b) {
    const double dx = a.x - b.x, dy = a.y - b.y;
    const double reach = a.r + b.r - touching_tolerance(a, b);
    if (!(reach > 0.0 && dx * dx + dy * dy < reach * reach)) return false;
    if (!should_collide(bodies[a.body].collider->filter, bodies[b.body].collider->filter)) {
      return false;
    }
    const std::pair key{std::min(a.body, b.body), std::max(a.body, b.body)};
    return !std::binary_search(linked.begin(), linked.end(), key);
  };
  std::size_t closed = 0;
  for (std::uint32_t i = 0; i < discs.size(); ++i) {
    const Disc& d = discs[i];
    // Close the discs whose interval ends left of this one's start: no later disc meets them.
    for (; closed < by_right.size() && discs[by_right[closed]].right < d.left; ++closed) {
      const Disc& c = discs[by_right[closed]];
      sides[c.dynamic ? 1 : 0].open.erase({c.y, by_right[closed]});
    }
    for (int side = d.dynamic ? 0 : 1; side < 2; ++side) {
      const Side& s = sides[side];
      const double reach = d.r + s.r_max, e = slack(d.y, reach);
      auto it = s.open.lower_bound({d.y - reach - e, 0});
      for (; it != s.open.end() && it->first <= d.y + reach + e; ++it) {
        const Disc& o = discs[it->second];
        if (overlap(d, o)) return std::pair{std::min(d.body, o.body), std::max(d.body, o.body)};
      }
    }
    sides[d.dynamic ? 1 : 0].open.emplace(d.y, i);
  }
  return std::nullopt;
}

std::optional<std::pair<std::size_t, std::size_t>> first_disc_overlap(const WorldDef& def) {
  if (!def.settings.contacts) return std::nullopt;
  return first_disc_overlap(def.bodies, def.links);
}

}  // namespace fixstep
