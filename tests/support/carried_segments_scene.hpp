// A scene of segments carried by kinematic bodies, shared by the reader's tests
// (test_scene_segments.cpp) and the writer's (test_scene_writer.cpp).
#pragma once

#include <string>
#include <string_view>

namespace fixstep::test {

// Lines 1-27: a dynamic disc, a kinematic lift moving at (0.5, 2) m/s, a static floor body and
// a grid of two kinematic bodies deck[0,0] and deck[1,0] moving left at 1 m/s.
inline constexpr std::string_view carried_bodies = R"([world]
dt = 0.01
[[body]]
name = "ball"
mass = 1.0
position = [0.0, 5.0]
radius = 0.25
[[body]]
name = "lift"
type = "kinematic"
position = [0.0, 0.0]
velocity = [0.5, 2.0]
[[body]]
name = "floor"
type = "static"
position = [0.0, -5.0]
[[grid]]
name = "deck"
columns = 2
rows = 1
origin = [10.0, 0.0]
spacing = [1.0, 1.0]
body = { type = "kinematic", velocity = [-1.0, 0.0] }
# the level: from line 28
#
#
#
)";

// Segment 0 carried by the lift, 1 static; polyline 0 (segments 2, 3) carried by the lift,
// polyline 1 (closed: segments 4, 5, 6) by deck[1,0], polyline 2 (segment 7) static.
inline const std::string carried_level = std::string(carried_bodies) + R"([[segment]]
a = [-1.0, 0.0]
b = [1.0, 0.0]
friction = 0.5
body = "lift"
[[segment]]
a = [-10.0, -6.0]
b = [10.0, -6.0]
[[polyline]]
points = [[-1.0, 1.0], [0.0, 1.5], [1.0, 1.0]]
friction = 0.3
body = "lift"
[[polyline]]
points = [[9.0, -1.0], [12.0, -1.0], [12.0, 1.0]]
closed = true
body = "deck[1,0]"
[[polyline]]
points = [[-3.0, -4.0], [3.0, -4.0]]
)";

}  // namespace fixstep::test
