// Scene files: the drawing-only keys that name images (a body's sprite, [view]
// background_image) and style level geometry (a segment's or polyline's color and width). The
// images are checked where the scene names them (io's check_png_file), so that a bad one is a
// located scene error, not a failure of the first frame. See docs/SCENES.md.
#include <filesystem>
#include <set>
#include <string>

#include "fixstep/core/components.hpp"
#include "fixstep/core/segment.hpp"
#include "fixstep/io/file_read.hpp"
#include "fixstep/io/png_check.hpp"
#include "scene_reader.hpp"

namespace fixstep::scene_detail {

namespace {

/// `written` (a path as the scene gives it) relative to the folder of the scene file `scene`,
/// unless absolute or the scene has no folder. A scene embedded in a recording is parsed under
/// the name "FILE (embedded in RECORDING)" (fixstep replay, the page, app::run): its folder is
/// FILE's, where the recording's scene was when it was recorded.
std::string resolved(const std::string& scene, const std::string& written) {
  const std::filesystem::path p(written);
  const std::size_t embedded = scene.find(" (embedded in ");
  const std::string file =
      embedded != std::string::npos && scene.ends_with(")") ? scene.substr(0, embedded) : scene;
  const std::filesystem::path base = std::filesystem::path(file).parent_path();
  return p.is_absolute() || base.empty() ? written : (base / p).string();
}

/// Why the image at `file` cannot be drawn ("" when it can), with its size.
std::string image_problem(const std::string& file, PngSize& size) {
  try {
    size = check_png_file(file);
    return {};
  } catch (const FileReadError& e) {
    if (e.kind() == FileReadError::Kind::missing) return "no such file";
    if (e.kind() == FileReadError::Kind::too_large)
      return fmt::format("larger than {} bytes", max_image_file_bytes);
    return e.reason();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
}

}  // namespace

std::string parse_image(const Reader& r, const toml::table& t, std::string_view key,
                        const std::string& path) {
  const std::optional<std::string> written = r.string(t, key, path);
  const toml::node& n = *t.get(key);
  if (!written || written->empty()) {
    r.fail(n.source(), path, "expected the path of a PNG file, found an empty string");
  }
  std::string file = resolved(r.file(), *written);  // not const: returned by move
  PngSize size;
  if (const std::string why = image_problem(file, size); !why.empty()) {
    r.fail(n.source(), path, fmt::format("image {}: {}", file, why));
  }
  return file;
}

void parse_segment_looks(const Reader& r, const toml::table& t, const std::string& path,
                         std::span<SegmentDef> segments) {
  Rgba8 color{0, 0, 0, 0};
  if (t.get("color")) color = parse_color(r, t, "color", path + ".color");
  double width = 0.0;
  if (auto w = r.number(t, "width", path + ".width")) {
    r.require(*w > 0.0 && *w <= max_state_magnitude, t, "width", path + ".width",
              "> 0 m and <= 1e12 m (the line's width)", *w);
    width = *w;
  }
  for (SegmentDef& s : segments) s.color = color, s.width = width;
}

void check_image_budget(const Reader& r, const toml::table& doc, const Scene& scene) {
  std::set<std::string> seen;
  std::size_t bytes = 0;
  // Each new image counted; the one beyond a bound is refused where the scene names it.
  auto count = [&](const std::string& file, std::size_t line, const std::string& key) {
    if (!seen.insert(file).second) return;
    PngSize size;
    (void)image_problem(file, size);  // checked when parsed
    bytes += std::size_t(size.width) * std::size_t(size.height) * 4;
    if (seen.size() > max_images) {
      throw SceneError(r.file(), line, 0, key,
                       fmt::format("image {}: more than {} images in one scene", file, max_images));
    }
    if (bytes > max_image_bytes) {
      throw SceneError(r.file(), line, 0, key,
                       fmt::format("image {}: the scene's images would take more than {} bytes of "
                                   "pixels (4 a pixel)",
                                   file, max_image_bytes));
    }
  };
  if (const auto& image = scene.view.background_image) {
    const toml::node* n = doc.at_path("view.background_image").node();
    count(*image, n ? n->source().begin.line : 0, "view.background_image");
  }
  for (std::size_t i = 0; i < scene.def.bodies.size(); ++i) {
    const std::optional<Appearance>& a = scene.def.bodies[i].appearance;
    if (!a || a->sprite.empty()) continue;
    const std::size_t line = i < scene.source.body_lines.size() ? scene.source.body_lines[i] : 0;
    count(a->sprite, line, fmt::format("body[{}].sprite", i));
  }
}

}  // namespace fixstep::scene_detail
