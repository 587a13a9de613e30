// shape_distance: to be written.
#include "shape_geom.hpp"
