// Scene files: the [view] table (what part of the world the frames show). See README
// "Scene format".
#include <cmath>

#include "scene_reader.hpp"

namespace fixstep::scene_detail {

void parse_view(Reader& r, const toml::table& doc, Scene& scene) {
  const toml::table* view = r.table(doc, "view", "view");
  if (!view) return;
  r.check_keys(*view, "view", {"center", "width"});
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
