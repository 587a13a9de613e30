// What a world is built from (WorldDef): the bodies, links, planes, segments and joints, and the
// settings and precision it steps with, written in code or read from a scene file
// (fixstep/scene/scene.hpp). World(def) builds it (fixstep/core/world.hpp).
#pragma once

#include <span>
#include <string_view>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/entity.hpp"
#include "fixstep/core/joint.hpp"
#include "fixstep/core/segment.hpp"
#include "fixstep/core/types.hpp"
#include "fixstep/core/world_settings.hpp"

namespace fixstep {

/// Everything a world is built from: what a scene file describes (Scene::def, scene.hpp), or
/// what a program writes in code. World(def) is the one way to make a world: it checks the
/// definition (definition_checks.hpp) and builds it.
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
  /// Joints between bodies with shapes (JointDef; bodies by the handles add_body returned),
  /// created after the links, in order: World::defined_joints()[i] is joints[i]'s handle.
  std::vector<JointDef> joints;
  /// Whether the stability guard warns instead of refusing (World(def) then builds an unstable
  /// world and reports the finding in World::warnings()): for demos that show a blow-up on
  /// purpose.
  bool allow_unstable = false;

  /// A definition of no bodies, links, planes or segments in `precision` stepped with
  /// `settings`: the start of a world a program fills after making it (World::create_body,
  /// add_plane, ...), World(WorldDef::empty(precision, settings)).
  [[nodiscard]] static WorldDef empty(Precision precision, const WorldSettings& settings) {
    WorldDef def;
    def.precision = precision;
    def.settings = settings;
    return def;
  }

  /// Appends `body` and returns the handle World(def) will give it (World::defined_bodies()
  /// lists the same handles), for the links and per-body inputs a program writes before the
  /// world exists.
  Entity add_body(BodyDef body);
  /// The handle World(def) will give the first body named `name` (World::find does the same in
  /// the world), or null_entity when no body has that name: for a game's setup() to keep the
  /// handles of a scene's bodies instead of finding them by name every tick.
  [[nodiscard]] Entity find_body(std::string_view name) const;
  /// The handle World(def) will give the first joint named `name`, or a null Joint.
  [[nodiscard]] Joint find_joint(std::string_view name) const;
  /// Appends a link between two bodies add_body returned; World(def) validates it.
  void add_link(Entity a, Entity b, const LinkSpring& spring) {
    links.push_back(LinkDef{a, b, spring});
  }
  /// Appends the segments of a polyline through `points` (polyline_segments: throws
  /// std::invalid_argument for too few points or a zero-length segment), carried by `body`
  /// (a handle add_body returned, of a kinematic body) or static (null), each one-way
  /// (SegmentDef::one_way) when `one_way`.
  void add_polyline(std::span<const Vec2> points, double restitution, double friction,
                    bool closed = false, Entity body = {}, bool one_way = false);
};

}  // namespace fixstep
