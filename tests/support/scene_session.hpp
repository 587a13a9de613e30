// Session for a loaded scene, as `fixstep render` opens it (cli/render_command.cpp,
// session_settings): its world, its [view] and its file name in the HUD. For tests and benchmarks.
#pragma once

#include <filesystem>

#include "fixstep/app/scene_view_settings.hpp"
#include "fixstep/app/session.hpp"
#include "fixstep/scene/scene.hpp"

namespace fixstep::testing {

inline Session scene_session(const Scene& scene, int width, int height) {
  SessionSettings s{.width = width,
                    .height = height,
                    .title = std::filesystem::path(scene.file).filename().string(),
                    .view_center = scene.view.center,
                    .view_width = scene.view.width};
  apply_scene_view_style(scene.view, s);
  return Session(scene.def, s);
}

}  // namespace fixstep::testing
