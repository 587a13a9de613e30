// fixstep::scene, all of it: TOML scenes to and from a WorldDef, input scripts, stability advice.
// One include for a program that uses the whole library; each header below stands alone.
#pragma once

#include "fixstep/scene/input_script.hpp"
#include "fixstep/scene/scene.hpp"
#include "fixstep/scene/scene_stability.hpp"
#include "fixstep/scene/scene_writer.hpp"
#include "fixstep/scene/suggest.hpp"
