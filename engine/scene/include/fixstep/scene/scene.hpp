// Scene files: TOML describing a world, its bodies and the view. See README "Scene format".
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"

namespace fixstep {

/// A scene that cannot be used. what() reads "FILE:LINE:COLUMN: KEY: MESSAGE" (column or line
/// left out when unknown), e.g.
/// "spring.toml:12:13: body[0].spring.stiffness: expected a number, found a string".
class SceneError : public std::runtime_error {
 public:
  SceneError(std::string file, std::size_t line, std::size_t column, std::string key,
             const std::string& message);
  [[nodiscard]] const std::string& file() const { return file_; }
  [[nodiscard]] std::size_t line() const { return line_; }       ///< 1-based; 0 = unknown
  [[nodiscard]] std::size_t column() const { return column_; }   ///< 1-based; 0 = unknown
  [[nodiscard]] const std::string& key() const { return key_; }  ///< e.g. "world.dt"

 private:
  std::string file_;
  std::size_t line_, column_;
  std::string key_;
};

/// Largest |x| and |y| of [view] center, m: the runtime guard's max_state_magnitude (no body
/// is ever drawn beyond it).
inline constexpr double max_view_center = max_state_magnitude;
/// Narrowest [view] width, m (a micron: below it a frame's pixels are smaller than 10^-10 m).
inline constexpr double min_view_width = 1e-6;
/// Widest [view] width, m: ten times max_view_center, so the widest view holds every place a
/// body can be.
inline constexpr double max_view_width = 10.0 * max_view_center;
/// Narrowest [view] width as a fraction of the centre's distance from the origin (its larger
/// coordinate): a narrower view of a point that far out could not tell its pixels or its grid
/// lines apart in doubles (about 16 digits).
inline constexpr double min_view_width_ratio = 1e-9;

/// Where the [view] table puts the HUD (hud = "top_left", ..., "off").
enum class SceneHud : std::uint8_t { top_left, top_right, bottom_left, bottom_right, off };

/// How the [view] table asks for joints to be drawn (joints = "off", "anchors", "limits"): not
/// at all; a mark at each anchor (the default); the marks and each joint's limits.
enum class SceneJoints : std::uint8_t { off, anchors, limits };

/// The engine's HUD lines a [view] hud_lines array names, as bits (the app library's HudLine
/// values): "title", "time", "integrator", "energy", "controls".
inline constexpr std::uint32_t scene_hud_title = 1u << 0;
inline constexpr std::uint32_t scene_hud_time = 1u << 1;
inline constexpr std::uint32_t scene_hud_integrator = 1u << 2;
inline constexpr std::uint32_t scene_hud_energy = 1u << 3;
inline constexpr std::uint32_t scene_hud_controls = 1u << 4;

/// Narrowest and widest [view] hud_scale, px per font pixel (the renderer's limits).
inline constexpr double min_scene_hud_scale = 1.0;
inline constexpr double max_scene_hud_scale = 4.0;

/// The optional [view] table: what part of the world the frames show, and how. The loader
/// refuses (SceneError at the key) a center coordinate beyond ±max_view_center, a width outside
/// [min_view_width, max_view_width], and a width below min_view_width_ratio × the center's
/// larger coordinate: each bounds the work and memory of drawing a frame. Each field is unset
/// when the table does not name it: the program's choice, else the default, applies.
struct SceneView {
  std::optional<Vec2> center;   ///< m; default: centre of the bodies and anchors
  std::optional<double> width;  ///< visible width, m; default: fits bodies and spring ranges
  /// background = "#rrggbb" (or "#rrggbbaa": the alpha is ignored, frames are opaque).
  std::optional<Rgba8> background;
  std::optional<bool> grid;       ///< grid = true/false: grid lines every power of ten metres
  std::optional<bool> axes;       ///< axes = true/false: the lines x = 0 and y = 0
  std::optional<bool> scale_bar;  ///< scale_bar = true/false
  std::optional<SceneHud> hud;    ///< hud = "top_left" | ... | "bottom_right" | "off"
  /// hud_scale = 1 .. 4: the HUD's text, px per font pixel.
  std::optional<double> hud_scale;
  /// hud_lines = ["title", "time", ...]: which engine lines the HUD may show (scene_hud_* bits;
  /// [] none: only a program's own lines).
  std::optional<std::uint32_t> hud_lines;
  /// joints = "off" | "anchors" | "limits": how joints are drawn (default "anchors").
  std::optional<SceneJoints> joints;
  /// background_image = "tiles.png": a PNG tiled over the background, anchored to the world
  /// (the path resolved against the scene file's folder, checked as a body's sprite).
  std::optional<std::string> background_image;
  /// background_tile = 2.0: a background tile's width and height, m (> 0; default 1).
  std::optional<double> background_tile;
};

/// Where each part of a scene was declared, for messages: line numbers (0 if not from a file)
/// parallel to the definition's lists.
struct SceneSourceMap {
  /// Line of each body's table: its [[body]], or the generator that made it.
  std::vector<std::size_t> body_lines;
  std::vector<std::size_t> link_lines;  ///< line of each link's table
  /// Where each link was declared: "spring[3]" for a [[spring]] table, "chain[0].link",
  /// "grid[1].shear", ... for generated links (empty if not from a file).
  std::vector<std::string> link_keys;
  std::vector<std::size_t> plane_lines;  ///< line of each [[plane]] table
  /// Line of each segment's table: its [[segment]], or the [[polyline]] that made it.
  std::vector<std::size_t> segment_lines;
  std::vector<std::size_t> joint_lines;  ///< line of each [[joint]] table
};

/// A parsed, validated scene: the WorldDef it describes (def: World(scene.def) builds its world,
/// checking it; scene_stability.hpp locates the stability guard's findings in the file), plus
/// its view and its source map. Its settings keep the dissipation account
/// (WorldSettings::track_dissipation), so a scene's summaries and HUD show the energy balance.
/// def holds:
///   - settings: [world] dt (s), integrator, substeps, ...; [contacts] (settings.contacts);
///   - bodies: [[body]] tables in file order, then the bodies of [[chain]] and [[grid]] tables
///     (in file order, each in its own order); names unique;
///   - links: those of [[chain]] and [[grid]] tables, then the [[spring]] tables, by the
///     handles World(def) gives the bodies;
///   - planes: [[plane]] tables in file order: static half-planes (normals normalised) that
///     bodies with a radius (a Collider) bounce on;
///   - segments: [[segment]] tables in file order, then the segments of [[polyline]] tables
///     (in file order, each joined by ghost vertices: SegmentDef); a table's `body` names the
///     kinematic body carrying its segments (SegmentDef::body, that body's handle);
///   - joints: [[joint]] tables in file order (JointDef; body_a and body_b the handles of the
///     bodies they name, null for the world where one is left out).
struct Scene {
  /// What the file describes; [world] allow_unstable is def.allow_unstable (the stability guard
  /// warns instead of refusing, for demos that show blow-ups on purpose).
  WorldDef def;
  std::string file;  ///< where it came from (for messages)
  SceneView view;
  SceneSourceMap source;
  std::vector<std::string> warnings;  ///< non-fatal findings (unknown keys, with suggestions)
  /// The bytes the scene was parsed from, exactly (at most max_scene_bytes): what a recording
  /// of its world embeds (Recording::scene_text), so that it replays without the file.
  std::string text;
};

/// Largest scene file accepted, bytes.
inline constexpr std::size_t max_scene_bytes = 4u << 20;
/// Most bodies a scene may have, [[body]] tables and generated bodies together.
inline constexpr std::size_t max_scene_bodies = 1'000'000;
/// Most links (springs between bodies) a scene may have.
inline constexpr std::size_t max_scene_links = 4'000'000;

/// Reads and validates a scene file. Throws SceneError (file, line, column, key) for syntax
/// errors, missing or mistyped keys, vectors that are not [x, y], non-finite numbers, values out
/// of range (mass <= 0, negative stiffness/damping/drag, dt <= 0), unknown integrator or
/// precision, duplicate body names, springs given both as stiffness/damping and as
/// frequency/damping_ratio, [[spring]] tables naming an unknown body or one body twice, a
/// rest-length spring between bodies that start at the same point, [[plane]] tables with a
/// zero normal, restitution outside [0, 1] or negative friction (in [[plane]], [[segment]],
/// [[polyline]], [contacts] and bodies), a [[segment]] whose ends coincide, a [[polyline]]
/// with fewer than 2 points (3 when closed) or a point repeating the one before it, a [[segment]]
/// or [[polyline]] whose body is not a string, names no body (with the closest name) or names
/// one that is not kinematic, [[joint]] tables with an unknown type (with the closest one), a key
/// their type does not use, no body, one body twice, an unknown body (with the closest name) or
/// one without shapes, limits outside their range (revolute: [-π, π]) or lower > upper, a
/// negative maximum, frequency, damping ratio, break force or torque, a length <= 0, a zero
/// axis, a wheel without frequency > 0, or more than max_joints of them (docs/SCENES.md,
/// "Joints"), an unknown body type (with the closest valid one),
/// collide/restitution/friction on a body without radius, discs overlapping where they start
/// when [contacts] is on (naming both and the overlap in m; first_disc_overlap), generators beyond
/// max_scene_bodies / max_scene_links, and unreadable, binary or oversized files. Warns
/// (Scene::warnings) about unknown keys, a mass, spring, gravity, force or drag given to a static
/// or kinematic body (dropped), a static body's velocity (set to zero), springs and joints between
/// two such bodies (or such a body and the world), a joint's damping_ratio without frequency, and
/// [contacts] in a scene without discs.
///
/// Generators of many bodies take time (seconds for 10^6 bodies and 2·10^6 links):
/// every 65 536 bodies or links they report progress to the calling thread's WorkProgressScope
/// ("generating the scene", unit "body" or "link"; fixstep/core/work_progress.hpp) and throw
/// StopRequested when a stop is pending (fixstep/core/stop_request.hpp).
[[nodiscard]] Scene load_scene(const std::filesystem::path& file);
/// As load_scene, from text; `source_name` is used in messages.
[[nodiscard]] Scene parse_scene(std::string_view text, const std::string& source_name);

}  // namespace fixstep
