// shape: to be written.
#include "shape_geom.hpp"
