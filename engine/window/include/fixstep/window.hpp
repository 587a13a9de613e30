// fixstep::window, all of it: the SDL2 window presenting rendered frames.
// One include for a program that uses the whole library; each header below stands alone.
#pragma once

#include "fixstep/window/window.hpp"
