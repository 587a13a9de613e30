// Scene files: the [view] table (what part of the world the frames show, and how: background,
// grid, axes, scale bar, the HUD's corner, scale and lines, the joints). See README "Scene
// format".
#include <array>
#include <cmath>
#include <string_view>
#include <utility>

#include "scene_reader.hpp"

namespace fixstep::scene_detail {

namespace {

constexpr std::array<std::pair<std::string_view, SceneHud>, 5> hud_places{{
    {"top_left", SceneHud::top_left},
    {"top_right", SceneHud::top_right},
    {"bottom_left", SceneHud::bottom_left},
    {"bottom_right", SceneHud::bottom_right},
    {"off", SceneHud::off},
}};

constexpr std::array<std::pair<std::string_view, std::uint32_t>, 5> hud_line_names{{
    {"title", scene_hud_title},
    {"time", scene_hud_time},
    {"integrator", scene_hud_integrator},
    {"energy", scene_hud_energy},
    {"controls", scene_hud_controls},
}};

constexpr std::array<std::pair<std::string_view, SceneJoints>, 3> joint_views{{
    {"off", SceneJoints::off},
    {"anchors", SceneJoints::anchors},
    {"limits", SceneJoints::limits},
}};

/// "a", "b" and "c" for messages.
template <std::size_t N, class T>
std::string names_of(const std::array<std::pair<std::string_view, T>, N>& table) {
  std::string out;
  for (std::size_t i = 0; i < N; ++i) {
    out += fmt::format("{}\"{}\"", i == 0 ? "" : (i + 1 == N ? " or " : ", "), table[i].first);
  }
  return out;
}

/// hud = "top_left" | "top_right" | "bottom_left" | "bottom_right" | "off".
void parse_hud_place(const Reader& r, const toml::table& view, SceneView& out) {
  const auto place = r.string(view, "hud", "view.hud");
  if (!place) return;
  for (const auto& [name, value] : hud_places) {
    if (*place == name) {
      out.hud = value;
      return;
    }
  }
  r.fail(view.get("hud")->source(), "view.hud",
         fmt::format("expected {}, found \"{}\"", names_of(hud_places), *place));
}

/// joints = "off" | "anchors" | "limits".
void parse_joint_view(const Reader& r, const toml::table& view, SceneView& out) {
  const auto name = r.string(view, "joints", "view.joints");
  if (!name) return;
  for (const auto& [spelling, value] : joint_views) {
    if (*name == spelling) {
      out.joints = value;
      return;
    }
  }
  r.fail(view.get("joints")->source(), "view.joints",
         fmt::format("expected {}, found \"{}\"", names_of(joint_views), *name));
}

/// hud_lines = ["title", "time", "integrator", "energy", "controls"] (any of them, once each).
void parse_hud_lines(const Reader& r, const toml::table& view, SceneView& out) {
  const toml::node* n = view.get("hud_lines");
  if (!n) return;
  const toml::array* list = n->as_array();
  if (!list) {
    r.fail(n->source(), "view.hud_lines",
           fmt::format("expected an array of line names ({}), found {}", names_of(hud_line_names),
                       found(*n)));
  }
  std::uint32_t bits = 0;
  for (std::size_t i = 0; i < list->size(); ++i) {
    const toml::node& item = *list->get(i);
    const std::string path = fmt::format("view.hud_lines[{}]", i);
    const toml::value<std::string>* name = item.as_string();
    if (!name) r.fail(item.source(), path, fmt::format("expected a string, found {}", found(item)));
    std::uint32_t bit = 0;
    for (const auto& [line, value] : hud_line_names)
      if (name->get() == line) bit = value;
    if (bit == 0) {
      r.fail(item.source(), path,
             fmt::format("expected {}, found \"{}\"", names_of(hud_line_names), name->get()));
    }
    if ((bits & bit) != 0)
      r.fail(item.source(), path, fmt::format("\"{}\" is named twice", name->get()));
    bits |= bit;
  }
  out.hud_lines = bits;
}

/// background, grid, axes, scale_bar, hud, hud_scale, hud_lines, joints.
void parse_view_style(const Reader& r, const toml::table& view, SceneView& out) {
  if (view.contains("background"))
    out.background = parse_color(r, view, "background", "view.background");
  out.grid = r.boolean(view, "grid", "view.grid");
  out.axes = r.boolean(view, "axes", "view.axes");
  out.scale_bar = r.boolean(view, "scale_bar", "view.scale_bar");
  parse_hud_place(r, view, out);
  if (auto scale = r.number(view, "hud_scale", "view.hud_scale")) {
    r.require(
        *scale >= min_scene_hud_scale && *scale <= max_scene_hud_scale, view, "hud_scale",
        "view.hud_scale",
        fmt::format("{:g} .. {:g} (px per font pixel)", min_scene_hud_scale, max_scene_hud_scale),
        *scale);
    out.hud_scale = *scale;
  }
  parse_hud_lines(r, view, out);
  parse_joint_view(r, view, out);
  if (view.contains("background_image"))
    out.background_image = parse_image(r, view, "background_image", "view.background_image");
  if (auto tile = r.number(view, "background_tile", "view.background_tile")) {
    r.require(*tile > 0.0 && *tile <= max_view_width, view, "background_tile",
              "view.background_tile", fmt::format("> 0 m and <= {:g} m", max_view_width), *tile);
    out.background_tile = *tile;
  }
}

}  // namespace

void parse_view(Reader& r, const toml::table& doc, Scene& scene) {
  const toml::table* view = r.table(doc, "view", "view");
  if (!view) return;
  r.check_keys(*view, "view",
               {"center", "width", "background", "grid", "axes", "scale_bar", "hud", "hud_scale",
                "hud_lines", "joints", "background_image", "background_tile"});
  parse_view_style(r, *view, scene.view);
  // Bounded before any frame is drawn (SceneView): a view of a point 10^300 m out, or
  // 10^-300 m wide, has no pixels to draw.
  scene.view.center = r.vec2(*view, "center", "view.center");
  double far = 0.0;  // m, the centre's larger coordinate
  if (const auto& c = scene.view.center) {
    const toml::array& xy = *view->get("center")->as_array();
    for (int i = 0; i < 2; ++i) {
      const double v = i == 0 ? c->x : c->y;
      if (std::abs(v) > max_view_center) {
        r.fail(xy.get(static_cast<std::size_t>(i))->source(), fmt::format("view.center[{}]", i),
               fmt::format("must be within ±{:g} m, where bodies can be (the runtime guard's "
                           "limit; got {})",
                           max_view_center, v));
      }
      far = std::max(far, std::abs(v));
    }
  }
  if (auto w = r.number(*view, "width", "view.width")) {
    r.require(*w > 0.0, *view, "width", "view.width", "> 0 m", *w);
    r.require(*w >= min_view_width && *w <= max_view_width, *view, "width", "view.width",
              fmt::format("{:g} .. {:g} m", min_view_width, max_view_width), *w);
    r.require(*w >= min_view_width_ratio * far, *view, "width", "view.width",
              fmt::format(">= {:g} m for a center {:g} m out ({:g} of its distance: a "
                          "narrower view there cannot place its pixels); move the center "
                          "closer to the origin or widen the view",
                          min_view_width_ratio * far, far, min_view_width_ratio),
              *w);
    scene.view.width = *w;
  }
}

}  // namespace fixstep::scene_detail
