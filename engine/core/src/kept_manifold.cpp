// Contact recycling (kept_manifold.hpp).
#include "kept_manifold.hpp"

#include <cmath>

namespace fixstep::detail {

KeptManifold keep_manifold(std::uint64_t pair, const Manifold& m, const Pose& ta, double angle_a,
                           const Pose& tb, double angle_b, double speculative) {
  KeptManifold k;
  k.pair = pair;
  k.at = untransform(ta, tb.p);
  k.turn = angle_b - angle_a;
  k.speculative = speculative;
  k.normal = unrotate(ta.q, m.normal);
  k.count = m.count;
  for (int i = 0; i < m.count; ++i) {
    const ManifoldPoint& p = m.points[i];
    k.points[i] = {untransform(ta, p.point), untransform(tb, p.point), p.separation, p.id};
  }
  return k;
}

bool kept_holds(const KeptManifold& k, const Pose& ta, double angle_a, const Pose& tb,
                double angle_b, double extent_b, double speculative, double tolerance) {
  const Vec2 moved = untransform(ta, tb.p) - k.at;
  const double turned = std::abs(angle_b - angle_a - k.turn);
  double growth = speculative - k.speculative;
  if (growth < 0.0) growth = 0.0;                              // (a NaN stays one)
  const double room = tolerance - extent_b * turned - growth;  // for B's centre, m
  return room >= 0.0 && dot(moved, moved) <= room * room;      // |moved| <= room, squared
}

Manifold recycle(const KeptManifold& k, const Pose& ta, const Pose& tb) {
  Manifold m;
  m.count = k.count;
  m.normal = rotate(ta.q, k.normal);
  for (int i = 0; i < k.count; ++i) {
    const KeptManifold::Point& kp = k.points[i];
    const Vec2 pa = transform(ta, kp.on_a), pb = transform(tb, kp.on_b);
    ManifoldPoint& p = m.points[i];
    p.point = 0.5 * (pa + pb);
    p.anchor_a = p.point - ta.p, p.anchor_b = p.point - tb.p;
    p.separation = kp.separation + dot(pb - pa, m.normal);
    p.id = kp.id;
  }
  return m;
}

}  // namespace fixstep::detail
