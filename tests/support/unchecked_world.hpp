// A world built from a definition without World(def)'s checks: its bodies, links, planes and
// segments created one by one in definition order (so each gets the handle World(def) gives
// it, and the world steps to the same bits). For tests that start discs overlapping on purpose
// (a random pile), which World(def) refuses (check_overlaps).
#pragma once

#include "fixstep/core/components.hpp"
#include "fixstep/core/defined_bodies.hpp"
#include "fixstep/core/segment.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"

namespace fixstep::test {

inline World unchecked_world(const WorldDef& def) {
  World world(WorldDef::empty(def.precision, def.settings));
  for (const BodyDef& b : def.bodies) (void)world.create_body(b);
  for (const LinkDef& l : def.links) (void)world.create_link(l);
  for (const PlaneDef& p : def.planes) (void)world.add_plane(p);
  for (const SegmentDef& s : def.segments) (void)world.add_segment(s);
  return world;
}

}  // namespace fixstep::test
