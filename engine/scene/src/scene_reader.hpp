// The scene loader's internals, shared by scene.cpp ([world], [view], [[body]]) and
// scene_links.cpp ([[spring]], [[chain]], [[grid]]): the Reader that turns every problem into a
// SceneError with file:line:column and key path, and the parsers both files use. Internal to
// the engine: not installed.
#pragma once

#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <initializer_list>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "fixstep/core/components.hpp"
#include "fixstep/core/segment.hpp"
#include "fixstep/core/value_ranges.hpp"
#include "fixstep/scene/scene.hpp"
#include "fixstep/scene/suggest.hpp"

namespace fixstep::scene_detail {

/// How read_text_file names the kind of file in its messages.
struct FileKind {
  std::string_view noun;       ///< "scene file": "cannot open scene file (does it exist?)"
  std::string_view article;    ///< "a": "is a directory, not a scene file"
  std::string_view owner;      ///< "a scene": "file is larger than the N bytes a scene may have"
  std::string_view plural;     ///< "scenes": "file is N bytes; scenes are limited to M bytes"
  std::string_view extension;  ///< ".toml": the files a directory given instead is searched for
};

/// The whole text of `file`, at most max_bytes. Throws SceneError (file only, no line) when it
/// is a directory (naming the files in it with kind.extension), does not exist (suggesting the
/// closest name in its directory), cannot be opened or read, or is larger. Defined in
/// scene_text.cpp.
std::string read_text_file(const std::filesystem::path& file, std::size_t max_bytes,
                           const FileKind& kind);
/// `text` parsed as TOML. Throws SceneError for more than max_bytes, a fixstep recording, a NUL
/// byte (binary data), nesting deeper than max_toml_depth (toml_depth.hpp; checked before
/// toml++ parses, with line and column) and TOML syntax errors (with line and column, in plain
/// words, with advice for common slips). Defined in scene_text.cpp.
toml::table parse_toml(std::string_view text, const std::string& source_name, std::size_t max_bytes,
                       const FileKind& kind);

inline std::string_view type_name(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a float";
    case toml::node_type::boolean:
      return "a boolean";
    default:
      return "a date/time";
  }
}

/// What a node holds, for "expected ..., found ..." messages: its type, with the value when it
/// is a scalar: `a string ("fast")`, `a float (4.0)`, `an array of 3 elements`.
inline std::string found(const toml::node& n) {
  if (const toml::value<std::string>* s = n.as_string()) {
    std::string v = s->get().substr(0, 40);
    for (char& c : v) c = static_cast<unsigned char>(c) < 0x20 ? '?' : c;  // one line
    return fmt::format("a string (\"{}{}\")", v, s->get().size() > 40 ? "..." : "");
  }
  if (const toml::value<std::int64_t>* i = n.as_integer()) {
    return fmt::format("an integer ({})", i->get());
  }
  if (const toml::value<double>* f = n.as_floating_point()) {
    std::string v = fmt::format("{}", f->get());
    if (std::isfinite(f->get()) && v.find_first_of(".e") == std::string::npos) v += ".0";
    return fmt::format("a float ({})", v);
  }
  if (const toml::value<bool>* b = n.as_boolean()) return fmt::format("a boolean ({})", b->get());
  if (const toml::array* a = n.as_array()) {
    return a->empty()
               ? std::string("an empty array")
               : fmt::format("an array of {} element{}", a->size(), a->size() == 1 ? "" : "s");
  }
  return std::string(type_name(n));
}

/// "1 element", "3 elements".
inline std::string elements(std::size_t n) {
  return fmt::format("{} element{}", n, n == 1 ? "" : "s");
}

/// Walks a parsed document, turning every problem into a SceneError with its position.
class Reader {
 public:
  struct Warning {
    std::size_t line, column;
    std::string text;
  };

  explicit Reader(const std::string& file) : file_(file) {}

  [[nodiscard]] const std::string& file() const { return file_; }

  /// The warnings in file order.
  std::vector<std::string> take_warnings() {
    std::stable_sort(warnings_.begin(), warnings_.end(), [](const Warning& a, const Warning& b) {
      return a.line != b.line ? a.line < b.line : a.column < b.column;
    });
    std::vector<std::string> out;
    for (Warning& w : warnings_) out.push_back(std::move(w.text));
    return out;
  }

  [[noreturn]] void fail(const toml::source_region& where, const std::string& key,
                         const std::string& message) const {
    throw SceneError(file_, where.begin.line, where.begin.column, key, message);
  }

  /// A warning "FILE:LINE:COLUMN: KEY: MESSAGE" at `where`.
  void warn(const toml::source_region& where, const std::string& key, const std::string& message) {
    const auto& at = where.begin;
    warnings_.push_back({at.line, at.column,
                         fmt::format("{}:{}:{}: {}: {}", file_, at.line, at.column, key, message)});
  }

  /// Warns about keys of `table` not in `allowed`, suggesting the closest allowed key.
  void check_keys(const toml::table& table, const std::string& path,
                  std::initializer_list<std::string_view> allowed) {
    for (auto&& [key, node] : table) {
      const std::string_view k = key.str();
      if (std::find(allowed.begin(), allowed.end(), k) != allowed.end()) continue;
      const std::vector<std::string> candidates(allowed.begin(), allowed.end());
      const std::optional<std::string> best = closest(k, candidates);  // within two edits
      const std::string full = path.empty() ? std::string(k) : path + "." + std::string(k);
      warn(key.source(), full,
           fmt::format("unknown key ignored{}",
                       best ? fmt::format(" (did you mean `{}`?)", *best) : std::string()));
    }
  }

  /// Fails for a required key of `table` (at `table_path`) that is absent: `message` (e.g.
  /// "missing (required)") under the key path table_path.keys[0], then ": help" (what the key
  /// holds, e.g. "the mass in kg, e.g. mass = 1.0") when given. When the table holds another
  /// key within two edits of one of `keys` (a misspelling: the loader ignores it with a
  /// warning), the error is placed at that key and names both instead of the help:
  /// "stiffness: missing (required); found `stifness` — did you mean `stiffness`?".
  [[noreturn]] void fail_missing(const toml::table& table, const std::string& table_path,
                                 std::initializer_list<std::string_view> keys,
                                 const std::string& message, std::string_view help = {}) const {
    auto full = [&](std::string_view k) {
      return table_path.empty() ? std::string(k) : table_path + "." + std::string(k);
    };
    for (auto&& [name, node] : table) {
      for (const std::string_view k : keys) {
        const std::string_view found = name.str();
        if (found != k && edit_distance(found, k) <= 2) {
          fail(name.source(), full(k),
               fmt::format("{}; found `{}` — did you mean `{}`?", message, found, k));
        }
      }
    }
    fail(table.source(), full(*keys.begin()),
         help.empty() ? message : fmt::format("{}: {}", message, help));
  }

  /// A finite number (integer or float) at table[key]; nullopt when absent.
  std::optional<double> number(const toml::table& t, std::string_view key,
                               const std::string& path) const {
    const toml::node* n = t.get(key);
    if (!n) return std::nullopt;
    return number_node(*n, path);
  }

  double number_node(const toml::node& n, const std::string& path) const {
    if (!n.is_number()) {
      // A number in quotes ("0.01") is a string in TOML: say so.
      std::string hint;
      if (const toml::value<std::string>* s = n.as_string()) {
        const std::string& text = s->get();
        char* end = nullptr;
        (void)std::strtod(text.c_str(), &end);
        if (!text.empty() && end == text.c_str() + text.size()) {
          hint = fmt::format("; write the number without quotes: {}", text);
        }
      }
      fail(n.source(), path, fmt::format("expected a number, found {}{}", found(n), hint));
    }
    const double v = *n.value<double>();
    if (!std::isfinite(v)) fail(n.source(), path, fmt::format("must be finite (got {})", v));
    return v;
  }

  /// The number at t[key], t being the table at `table_path` (e.g. "body[0]"); fail_missing
  /// (with `help`) when absent.
  double required_number(const toml::table& t, const std::string& table_path, std::string_view key,
                         std::string_view help = {}) const {
    auto v = number(t, key, table_path + "." + std::string(key));
    if (!v) fail_missing(t, table_path, {key}, "missing (required)", help);
    return *v;
  }

  /// An integer in [lo, hi] at node n; `range` (e.g. ", the index of one of the chain's 3
  /// bodies") follows "must be lo .. hi" in the message. The type is checked first:
  /// value<std::int64_t>() of a float node converts it, which is undefined behaviour for floats
  /// beyond the int64 range (substeps = 1e30; found by fuzzing).
  std::int64_t integer_node(const toml::node& n, const std::string& path, std::int64_t lo,
                            std::int64_t hi, std::string_view range = {}) const {
    if (!n.is_integer()) {
      // 4.0 is a float in TOML: say how to write the integer.
      std::string hint;
      if (const toml::value<double>* f = n.as_floating_point()) {
        const double v = f->get();
        if (std::isfinite(v) && v == std::floor(v) && v >= double(lo) && v <= double(hi)) {
          hint = fmt::format("; write it without the decimal point: {:.0f}", v);
        }
      }
      fail(n.source(), path, fmt::format("expected an integer, found {}{}", found(n), hint));
    }
    const std::int64_t v = n.as_integer()->get();
    if (v < lo || v > hi) {
      fail(n.source(), path, fmt::format("must be {} .. {}{} (got {})", lo, hi, range, v));
    }
    return v;
  }

  Vec2 vec2_node(const toml::node& n, const std::string& path) const {
    const toml::array* a = n.as_array();
    if (!a || a->size() != 2) {
      fail(n.source(), path,
           a ? fmt::format("expected [x, y] (2 numbers), found {}", elements(a->size()))
             : fmt::format("expected [x, y], found {}", found(n)));
    }
    return Vec2{number_node(*a->get(0), path + "[0]"), number_node(*a->get(1), path + "[1]")};
  }

  std::optional<Vec2> vec2(const toml::table& t, std::string_view key,
                           const std::string& path) const {
    const toml::node* n = t.get(key);
    if (!n) return std::nullopt;
    return vec2_node(*n, path);
  }

  /// The boolean at t[key]; nullopt when absent. A value of another type is an error at the key
  /// ("expected true or false, found ...").
  std::optional<bool> boolean(const toml::table& t, std::string_view key,
                              const std::string& path) const {
    const toml::node* n = t.get(key);
    if (!n) return std::nullopt;
    if (!n->is_boolean()) {
      fail(n->source(), path, fmt::format("expected true or false, found {}", found(*n)));
    }
    return n->as_boolean()->get();
  }

  std::optional<std::string> string(const toml::table& t, std::string_view key,
                                    const std::string& path) const {
    const toml::node* n = t.get(key);
    if (!n) return std::nullopt;
    if (!n->is_string()) {
      fail(n->source(), path, fmt::format("expected a string, found {}", found(*n)));
    }
    return std::string(n->as_string()->get());
  }

  const toml::table* table(const toml::table& t, std::string_view key,
                           const std::string& path) const {
    const toml::node* n = t.get(key);
    if (!n) return nullptr;
    if (!n->is_table()) {
      fail(n->source(), path, fmt::format("expected a table, found {}", found(*n)));
    }
    return n->as_table();
  }

  /// The [[key]] tables of the document, or nullptr when there are none.
  const toml::array* tables(const toml::table& doc, std::string_view key) const {
    const toml::node* n = doc.get(key);
    if (!n) return nullptr;
    const toml::array* list = n->as_array();
    if (!list || !list->is_array_of_tables()) {
      // [body] (one pair of brackets) is a single table: the commonest slip.
      fail(n->source(), std::string(key),
           n->is_table() ? fmt::format("expected [[{0}]] tables, found a single [{0}] table; write "
                                       "[[{0}]] (double brackets) above each one",
                                       key)
                         : fmt::format("expected [[{}]] tables, found {}", key, found(*n)));
    }
    return list;
  }

  /// v must satisfy ok, else "must be <allowed> (got v)" at t[key].
  void require(bool ok, const toml::table& t, std::string_view key, const std::string& path,
               std::string_view allowed, double v) const {
    if (!ok) fail(t.get(key)->source(), path, fmt::format("must be {} (got {})", allowed, v));
  }

  /// A starting state value or length (m, m/s, rad, rad/s: `unit`) at t[key] (path; `index`
  /// 0 or 1 names a component of an [x, y] key, -1 a number) must be within
  /// max_state_magnitude, the runtime guard's range (value_ranges.hpp).
  void require_state(const toml::table& t, std::string_view key, const std::string& path, double v,
                     std::string_view unit, int index = -1) const {
    if (within_state(v)) return;
    const toml::node* n = t.get(key);
    if (index >= 0 && n->as_array()) n = n->as_array()->get(static_cast<std::size_t>(index));
    fail(n->source(), index >= 0 ? fmt::format("{}[{}]", path, index) : path,
         fmt::format("must be within +-{:g} {} (got {:g}): the runtime guard stops any state "
                     "beyond it",
                     max_state_magnitude, unit, v));
  }

  /// Both components of the [x, y] at t[key] (require_state).
  void require_state(const toml::table& t, std::string_view key, const std::string& path, Vec2 v,
                     std::string_view unit) const {
    require_state(t, key, path, v.x, unit, 0);
    require_state(t, key, path, v.y, unit, 1);
  }

  /// Narrowing to f32 must keep the value finite.
  void require_f32(double v, const toml::node* n, const std::string& path) const {
    if (std::abs(v) > double(std::numeric_limits<float>::max())) {
      fail(n->source(), path,
           fmt::format("{:g} overflows precision = \"f32\" (largest float {:g}); use a smaller "
                       "value, or precision = \"f64\" in [world]",
                       v, double(std::numeric_limits<float>::max())));
    }
  }

 private:
  const std::string& file_;
  std::vector<Warning> warnings_;
};

/// Fits the scene's precision: finite, and within float range for f32.
inline bool representable(double v, Precision p) {
  return std::isfinite(v) &&
         (p == Precision::f64 || std::abs(v) <= double(std::numeric_limits<float>::max()));
}

/// "a double" or "a float", for messages.
inline std::string_view precision_text(Precision p) {
  return p == Precision::f32 ? "a float" : "a double";
}

/// a and b are the same point in the scene's precision (the world compares them there).
inline bool same_point(Vec2 a, Vec2 b, Precision p) {
  if (p == Precision::f32) {
    return static_cast<float>(a.x) == static_cast<float>(b.x) &&
           static_cast<float>(a.y) == static_cast<float>(b.y);
  }
  return a.x == b.x && a.y == b.y;
}

/// Reads type, mass (required for a dynamic body), velocity, force, gravity, drag, radius,
/// draw_radius (the drawn radius, without a disc), color and the disc keys (collide, restitution,
/// friction) of t into def.
void parse_body_parts(Reader& r, const toml::table& t, const std::string& path, BodyDef& def);

/// Calls visit(table, path) for every body table of the document: each [[body]] ("body[i]")
/// and each generator's body template ("chain[i].body", "grid[i].body"); table is null where an
/// entry is not a table.
template <class Visit>
void for_each_body_table(const toml::table& doc, Visit&& visit) {
  auto each = [&](std::string_view list, auto&& f) {
    const toml::array* a = doc.get(list) ? doc.get(list)->as_array() : nullptr;
    for (std::size_t i = 0; a && i < a->size(); ++i) f(a->get(i), i);
  };
  each("body", [&](const toml::node* t, std::size_t i) {
    visit(t ? t->as_table() : nullptr, fmt::format("body[{}]", i));
  });
  for (const std::string_view generator : {"chain", "grid"}) {
    each(generator, [&](const toml::node* t, std::size_t i) {
      const toml::table* table = t ? t->as_table() : nullptr;
      const toml::node* body = table ? table->get("body") : nullptr;
      visit(body ? body->as_table() : nullptr, fmt::format("{}[{}].body", generator, i));
    });
  }
}

// --- bodies that touch (scene_contacts.cpp) ---
/// t.type ("dynamic", the default, "static" or "kinematic"); an unknown name is an error with
/// the closest valid one.
BodyType parse_body_type(const Reader& r, const toml::table& t, const std::string& path);
/// t.mass into def: required and > 0 kg for a dynamic body (unless its shapes have densities:
/// shapes_give_density); ignored with a warning for a static or kinematic one (which keeps the
/// default).
void parse_body_mass(Reader& r, const toml::table& t, const std::string& path, BodyDef& def);
/// collide (boolean), restitution (in [0, 1]) and friction (>= 0) of t into def.collider;
/// each is an error without a radius (def.collider unset).
void parse_disc_keys(const Reader& r, const toml::table& t, const std::string& path, BodyDef& def);
/// t[key] as filter bits: an integer whose 64-bit two's complement is the bit set (-1: every
/// category; hexadecimal allowed), nullopt when absent (scene_contacts.cpp).
std::optional<std::uint64_t> filter_bits(const Reader& r, const toml::table& t,
                                         std::string_view key, const std::string& path);
/// t.shape (one shape table, or an array of them: [[body.shape]]) into def.shapes, each
/// checked by shape_problem (its message at the key it names), with t.density (kg/m^2) for the
/// shapes that give none. A shape on a body with a radius (a disc) is an error, and so is a
/// density without a shape (scene_shapes.cpp).
void parse_body_shapes(Reader& r, const toml::table& t, const std::string& path, BodyDef& def);
/// t.mover (an inline table: max_floor_angle, step_height, snap_distance, push_force, skin) into
/// def.mover, each value checked at its key (mover_problem), and the body checked at t.mover: a
/// kinematic body with one capsule, not turning, step_height below the capsule's radius and
/// skin below half of it (scene_mover.cpp). Call after the shapes and the type are read.
void parse_body_mover(Reader& r, const toml::table& t, const std::string& path, BodyDef& def);
/// `mover = { ... }` with every field of b.mover, or "" without one (scene_mover.cpp).
[[nodiscard]] std::string mover_text(const BodyDef& b);
/// Whether body table t gives its shapes a density (t.density, or a density in a shape table):
/// then their densities give the mass and `mass` may be left out (scene_shapes.cpp).
[[nodiscard]] bool shapes_give_density(const toml::table& t);
/// angle (rad), angular_velocity (rad/s) and inertia (in [1e-100, 1e100] kg*m^2, an error without a
/// radius or a shape) of t into def, for rolling discs and bodies with shapes (scene_rolling.cpp).
void parse_rolling_keys(const Reader& r, const toml::table& t, const std::string& path,
                        BodyDef& def);
/// Warns at each disc's and point body's (and generator template's) angle, angular_velocity and
/// inertia: they act only with `[contacts] rolling = true` (a body with shapes always turns).
void warn_unused_rolling_keys(Reader& r, const toml::table& doc);
/// For a static or kinematic def: drops spring, gravity, force and drag with a warning at
/// their keys in t (they would move it), and a static body's non-zero velocity.
void drop_moving_parts(Reader& r, const toml::table& t, const std::string& path, BodyDef& def);
/// The [contacts] table into scene.settings.contacts (restitution in [0, 1], friction >= 0, both
/// default 0; sleep_speed > 0 m/s and sleep_time >= 0 s and under 1e9 ticks of scene.settings.dt,
/// each warned about without sleep = true), warning when no body is a disc. Without the table,
/// warns at each body's (and generator template's) restitution and friction: they act only in
/// disc-disc contacts. After the bodies and [world].
void parse_contacts(Reader& r, const toml::table& doc, Scene& scene);

/// The parameters of a spring table before the masses it acts on are known: stiffness k (N/m)
/// and damping b (N*s/m), or frequency f (Hz) and damping ratio ζ, converted with
/// spring_from_frequency for a mass (the body's, or a pair's reduced mass).
struct SpringSpec {
  bool by_frequency = false;
  double stiffness = 0.0, damping = 0.0;        ///< N/m, N*s/m
  double frequency = 0.0, damping_ratio = 0.0;  ///< Hz, dimensionless
  std::optional<double> rest_length;            ///< m; nullopt: the table's default
  const toml::node* frequency_node = nullptr;   ///< where conversion errors point
  std::string path;                             ///< e.g. "spring[2]"
};

/// The spring keys of t (stiffness, damping, frequency, damping_ratio; rest_length when
/// with_rest_length), without checking for unknown keys. Errors: both forms given (naming both
/// keys), neither stiffness nor frequency, negative or non-finite values, frequency <= 0.
SpringSpec parse_spring_spec(const Reader& r, const toml::table& t, const std::string& path,
                             bool with_rest_length);

/// The spring of spec acting on `mass` (kg), its rest length `rest` (m). Errors (at the
/// frequency key): a conversion that overflows a double, or a float with precision f32.
LinkSpring resolve_spring(const Reader& r, const SpringSpec& spec, double mass, double rest,
                          Precision precision);

/// Body names of a scene so far, with their indices, and what generated them (for messages).
struct BodyNames {
  std::unordered_map<std::string, std::size_t> index;
  /// Generators so far: "chain \"rope\" has rope[0] .. rope[39]", by name prefix.
  std::vector<std::pair<std::string, std::string>> generators;
  /// Generators so far: the index of their first body and their table ("grid[0]"), in order.
  std::vector<std::pair<std::size_t, std::string>> generated;
};

/// With [contacts] on, a SceneError at the later of two discs that overlap where they start
/// (first_disc_overlap), naming both, their lines and the overlap in m; the key is that body's
/// [[body]] table or its generator's. After the links (linked bodies may overlap).
void check_start_overlap(const Scene& scene, const BodyNames& names);

/// [[chain]] and [[grid]] tables: appends their bodies and links to the scene
/// (scene_generators.cpp).
void parse_generators(Reader& r, const toml::table& doc, Scene& scene, BodyNames& names);
/// [[plane]] tables: appends their planes (normals normalised) and lines to the scene
/// (scene_planes.cpp).
void parse_planes(Reader& r, const toml::table& doc, Scene& scene);
/// [[segment]] tables, then [[polyline]] tables (each as its segments, joined by ghost
/// vertices): appends their segments and lines to the scene (scene_segments.cpp). A table's
/// `body` names the kinematic body that carries its segments (SegmentDef::body), after every
/// body is known.
void parse_segments(Reader& r, const toml::table& doc, Scene& scene, const BodyNames& names);
/// The [view] table into scene.view (scene_view.cpp).
void parse_view(Reader& r, const toml::table& doc, Scene& scene);
/// t[key] (a string naming a PNG file, relative to the scene file's folder unless absolute) as
/// the path a renderer opens, checked (check_png_file: readable, a PNG, whole, at most
/// max_image_side px a side). Errors at the key, naming the file. Defined in scene_images.cpp.
std::string parse_image(const Reader& r, const toml::table& t, std::string_view key,
                        const std::string& path);
/// The drawing-only keys of a [[segment]] or [[polyline]] table: color ("#rrggbb[aa]") and width
/// (m, > 0) into each of segments[first, end). Defined in scene_images.cpp.
void parse_segment_looks(const Reader& r, const toml::table& t, const std::string& path,
                         std::span<SegmentDef> segments);
/// At most max_images distinct images, of at most max_image_bytes of pixels together, in the
/// scene (the bodies' sprites and the view's background). Defined in scene_images.cpp.
void check_image_budget(const Reader& r, const toml::table& doc, const Scene& scene);
/// t[key] (which must be present), "#rrggbb" or "#rrggbbaa", as a colour; `path` names the key
/// in errors (scene.cpp).
Rgba8 parse_color(const Reader& r, const toml::table& t, std::string_view key,
                  const std::string& path);
/// The scene index of the body named by node n (a [[spring]]'s bodies element, a segment's
/// body), else a located error at `key`: n not a string, or no body of that name (with the
/// closest name, and which generator makes names of that form) (scene_links.cpp).
std::size_t find_body(const Reader& r, const toml::node& n, const std::string& key,
                      const BodyNames& names);
/// [[spring]] tables: appends their links to the scene, after every body is known
/// (scene_links.cpp).
void parse_springs(Reader& r, const toml::table& doc, Scene& scene, const BodyNames& names);
/// [[joint]] tables: appends their joints (JointDef, bodies by the handles WorldDef::add_body
/// gives them) and lines to the scene, after every body is known; each key the joint's type does
/// not use, and each value out of its range, refused at its key (scene_joints.cpp).
void parse_joints(Reader& r, const toml::table& doc, Scene& scene, const BodyNames& names);

}  // namespace fixstep::scene_detail
