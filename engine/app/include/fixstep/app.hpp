// fixstep::app, all of it: a world being played: Session, key bindings, overlays, app::run for
// games. One include for a program that uses the whole library; each header below stands alone.
#pragma once

#include "fixstep/app/app.hpp"
#include "fixstep/app/game_level.hpp"
#include "fixstep/app/game_model.hpp"
#include "fixstep/app/game_play.hpp"
#include "fixstep/app/key_bindings.hpp"
#include "fixstep/app/overlay.hpp"
#include "fixstep/app/scene_view_settings.hpp"
#include "fixstep/app/session.hpp"
