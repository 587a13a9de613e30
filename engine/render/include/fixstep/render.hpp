// fixstep::render, all of it: drawing a world: the renderer, draw lists, trails, frame data.
// One include for a program that uses the whole library; each header below stands alone.
#pragma once

#include "fixstep/render/draw_list.hpp"
#include "fixstep/render/frame_data.hpp"
#include "fixstep/render/render.hpp"
#include "fixstep/render/trails.hpp"
#include "fixstep/render/user_events.hpp"
