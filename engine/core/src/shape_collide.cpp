// shape_collide: to be written.
#include "shape_geom.hpp"
