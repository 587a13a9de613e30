// A scene's [view] look (SceneView: background, grid, axes, scale bar, HUD corner, scale and
// lines, joints) as a Session's settings. Header-only: the browser page's app library has no scene
// loader of its own to link.
#pragma once

#include "fixstep/app/session.hpp"
#include "fixstep/scene/scene.hpp"

namespace fixstep {

static_assert(scene_hud_title == hud_title && scene_hud_time == hud_time &&
                  scene_hud_integrator == hud_integrator && scene_hud_energy == hud_energy &&
                  scene_hud_controls == hud_controls,
              "SceneView::hud_lines uses the HudLine bits");

/// The HUD corner of a [view] hud place (SceneHud::off has none: top_left).
[[nodiscard]] inline HudCorner hud_corner_of(SceneHud hud) {
  switch (hud) {
    case SceneHud::top_right:
      return HudCorner::top_right;
    case SceneHud::bottom_left:
      return HudCorner::bottom_left;
    case SceneHud::bottom_right:
      return HudCorner::bottom_right;
    default:
      return HudCorner::top_left;
  }
}

/// The renderer's JointView of a [view] joints value.
[[nodiscard]] inline JointView joint_view_of(SceneJoints joints) {
  switch (joints) {
    case SceneJoints::off:
      return JointView::off;
    case SceneJoints::limits:
      return JointView::limits;
    default:
      return JointView::anchors;
  }
}

/// Sets the fields of `s` that `view` names (its look only: centre and width are the caller's
/// to apply, as programs give their own precedence), leaving the others as they are.
inline void apply_scene_view_style(const SceneView& view, SessionSettings& s) {
  if (view.background) s.style.background = *view.background;
  if (view.grid) s.style.grid = *view.grid;
  if (view.axes) s.style.axes = *view.axes;
  if (view.scale_bar) s.style.scale_bar = *view.scale_bar;
  if (view.joints) s.style.joints = joint_view_of(*view.joints);
  if (view.hud) {
    s.show_hud = *view.hud != SceneHud::off;
    s.hud_corner = hud_corner_of(*view.hud);
  }
  if (view.hud_scale) s.hud_text_scale = static_cast<float>(*view.hud_scale);
  if (view.hud_lines) s.hud_lines = *view.hud_lines;
  if (view.background_image) s.style.background_image = *view.background_image;
  if (view.background_tile) s.style.background_tile = *view.background_tile;
}

}  // namespace fixstep
