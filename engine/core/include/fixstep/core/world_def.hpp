// What a world is built from (WorldDef): the bodies, links, planes and segments, and the
// settings and precision it steps with, written in code or read from a scene file
// (fixstep/scene/scene.hpp). World(def) builds it (fixstep/core/world.hpp).
#pragma once

#include <span>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/entity.hpp"
#include "fixstep/core/segment.hpp"
#include "fixstep/core/types.hpp"
#include "fixstep/core/world_settings.hpp"

namespace fixstep {

/// Everything a world is built from: what a scene file describes (see scene.hpp), or what a
/// program writes in code. The one definition the frame pipeline (Session, render library)
/// and the command line start from.
struct WorldDef {
  Precision precision = Precision::f64;
  WorldSettings settings;        ///< dt (s), integrator, substeps, ... (see WorldSettings)
  std::vector<BodyDef> bodies;   ///< in creation order (add_body)
  std::vector<LinkDef> links;    ///< springs between bodies, by the handles add_body returned
  std::vector<PlaneDef> planes;  ///< static half-planes (ground, walls) colliders stay out of
  /// Segments (level geometry, static or carried by a kinematic body: SegmentDef::body, a
  /// handle add_body returned) colliders stay out of; polylines as their segments
  /// (polyline_segments, add_polyline). After the planes in every order.
  std::vector<SegmentDef> segments;

  /// Appends `body` and returns the handle World(def) will give it (World::defined_bodies()
  /// lists the same handles), for the links and per-body inputs a program writes before the
  /// world exists.
  Entity add_body(BodyDef body);
  /// Appends a link between two bodies add_body returned; World(def) validates it.
  void add_link(Entity a, Entity b, const LinkSpring& spring) {
    links.push_back(LinkDef{a, b, spring});
  }
  /// Appends the segments of a polyline through `points` (polyline_segments: throws
  /// std::invalid_argument for too few points or a zero-length segment), carried by `body`
  /// (a handle add_body returned, of a kinematic body) or static (null).
  void add_polyline(std::span<const Vec2> points, double restitution, double friction,
                    bool closed = false, Entity body = {});
};

}  // namespace fixstep
