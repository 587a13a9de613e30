// shape_mass: to be written.
#include "shape_geom.hpp"
