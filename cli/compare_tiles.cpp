#include "compare_tiles.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fixstep/core/world_settings.hpp>
#include <fixstep/render/render.hpp>
#include <fixstep/scene/suggest.hpp>
#include <stdexcept>

namespace fixstep::cli {

namespace {

[[noreturn]] void bad_spec(std::string_view text, const std::string& what) {
  throw std::invalid_argument(
      fmt::format("{} in '{}'; expected "
                  "INTEGRATOR[@DT][:substeps=N][:precision=f32|f64][:split=per_stage|per_step], "
                  "e.g. rk4@1/30 or "
                  "implicit_euler@1/15:substeps=2",
                  what, text));
}

/// A whole decimal number of the text, or nullopt (no sign, no spaces, nothing after it).
std::optional<double> number(const std::string& s) {
  if (s.empty() || s.front() == '+' || s.front() == '-' || std::isspace(s.front())) return {};
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(s.c_str(), &end);
  if (end != s.c_str() + s.size() || errno == ERANGE || !std::isfinite(v)) return {};
  return v;
}

/// "0.02" or "1/60" as s.
double parse_dt(std::string_view spec, const std::string& s) {
  const std::size_t slash = s.find('/');
  const auto num = number(s.substr(0, slash));
  const auto den =
      slash == std::string::npos ? std::optional<double>(1.0) : number(s.substr(slash + 1));
  if (!num || !den || *den == 0.0) {
    bad_spec(spec, fmt::format("dt '{}' is not a number or a fraction A/B", s));
  }
  const double dt = *num / *den;
  if (!(dt > 0.0 && dt <= 1.0)) {
    bad_spec(spec, fmt::format("dt {} = {:g} s is outside (0, 1] s (as [world] dt)", s, dt));
  }
  return dt;
}

Integrator parse_integrator_of(std::string_view spec, const std::string& name) {
  if (const auto i = parse_integrator(name)) return *i;
  std::vector<std::string> names;
  for (const Integrator i : all_integrators) names.emplace_back(integrator_name(i));
  const auto best = closest(name, names);
  bad_spec(spec,
           best ? fmt::format("unknown integrator '{}' (did you mean {}?)", name, *best)
                : fmt::format("unknown integrator '{}' (valid: {})", name, integrator_names()));
}

/// One ":key=value" option of a spec.
void parse_option(std::string_view spec, const std::string& option, TileSpec& out) {
  const std::size_t eq = option.find('=');
  const std::string key = option.substr(0, eq);
  const std::string value = eq == std::string::npos ? "" : option.substr(eq + 1);
  if (key == "substeps") {
    const auto n = number(value);
    if (!n || *n != std::floor(*n) || *n < 1 || *n > 1'000'000) {
      bad_spec(spec, fmt::format("substeps '{}' is not a whole number 1..1000000", value));
    }
    out.substeps = static_cast<int>(*n);
  } else if (key == "precision") {
    out.precision = parse_precision(value);
    if (!out.precision) bad_spec(spec, fmt::format("precision '{}' is not f32 or f64", value));
  } else if (key == "split") {
    out.damping_split = parse_damping_split(value);
    if (!out.damping_split) {
      bad_spec(spec, fmt::format("split '{}' is not per_stage or per_step", value));
    }
  } else {
    const auto best = closest(key, std::vector<std::string>{"substeps", "precision", "split"});
    bad_spec(spec, fmt::format("unknown option '{}'{}", key,
                               best ? fmt::format(" (did you mean {}?)", *best) : ""));
  }
}

}  // namespace

TileSpec parse_tile_spec(std::string_view text) {
  TileSpec spec;
  spec.text = std::string(text);
  const std::string s(text);
  const std::size_t colon = s.find(':');
  const std::string head = s.substr(0, colon);
  const std::size_t at = head.find('@');
  spec.integrator = parse_integrator_of(text, head.substr(0, at));
  if (at != std::string::npos) spec.dt = parse_dt(text, head.substr(at + 1));
  for (std::size_t start = colon; start != std::string::npos;) {
    const std::size_t next = s.find(':', start + 1);
    parse_option(text, s.substr(start + 1, next == std::string::npos ? next : next - start - 1),
                 spec);
    start = next;
  }
  return spec;
}

std::string tile_spec_validator(const std::string& value) {
  try {
    (void)parse_tile_spec(value);
    return {};
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
}

Scene tile_scene(const Scene& base, const TileSpec& spec) {
  Scene s = base;
  s.def.settings.integrator = spec.integrator;
  if (spec.dt) s.def.settings.dt = *spec.dt;
  if (spec.substeps) s.def.settings.substeps = *spec.substeps;
  if (spec.precision) s.def.precision = *spec.precision;
  if (spec.damping_split) s.def.settings.damping_split = *spec.damping_split;
  return s;
}

std::string tile_label(const TileSpec& spec, const Scene& scene) {
  const std::size_t at = spec.text.find('@');
  const std::string dt = at == std::string::npos
                             ? fmt::format("{:g}", scene.def.settings.dt)
                             : spec.text.substr(at + 1, spec.text.find(':') - at - 1);
  return fmt::format(
      "{} @ {} s{}{}{}", integrator_name(scene.def.settings.integrator), dt,
      scene.def.settings.substeps > 1 ? fmt::format(" x{}", scene.def.settings.substeps) : "",
      scene.def.precision == Precision::f32 ? " f32" : "",
      scene.def.settings.damping_split == DampingSplit::per_step ? " per_step" : "");
}

std::size_t most_accurate(std::span<const Scene> tiles) {
  auto estimate = [](const Scene& s) {
    const double h = s.def.settings.dt / s.def.settings.substeps;
    const double e = std::pow(h, integrator_order(s.def.settings.integrator));
    return s.def.precision == Precision::f32 ? std::max(e, 1e-7) : e;
  };
  std::size_t best = 0;
  for (std::size_t i = 1; i < tiles.size(); ++i) {
    if (estimate(tiles[i]) < estimate(tiles[best])) best = i;
  }
  return best;
}

int TileGrid::x(std::size_t i) const {
  return static_cast<int>(i % static_cast<std::size_t>(columns)) * (tile_width + gap);
}

int TileGrid::y(std::size_t i) const {
  return static_cast<int>(i / static_cast<std::size_t>(columns)) * (tile_height + gap);
}

TileGrid tile_grid(int tiles, int width, int height) {
  TileGrid g;
  g.columns = tiles <= 3 ? tiles : (tiles == 4 ? 2 : 3);
  g.rows = (tiles + g.columns - 1) / g.columns;
  g.tile_width = (width - (g.columns - 1) * TileGrid::gap) / g.columns;
  g.tile_height = (height - (g.rows - 1) * TileGrid::gap) / g.rows;
  if (g.tile_width < min_frame_size || g.tile_height < min_frame_size) {
    throw std::invalid_argument(fmt::format(
        "--size {}x{} is too small for {} tiles: each would be {}x{} pixels, less "
        "than the {}x{} minimum",
        width, height, tiles, g.tile_width, g.tile_height, min_frame_size, min_frame_size));
  }
  return g;
}

void blit_tile(std::span<const std::uint8_t> tile, const TileGrid& grid, std::size_t i,
               std::span<std::uint8_t> frame, int frame_width) {
  const auto row_bytes = static_cast<std::size_t>(grid.tile_width) * 4;
  const std::size_t x = static_cast<std::size_t>(grid.x(i)) * 4;
  for (int r = 0; r < grid.tile_height; ++r) {
    const std::size_t dst =
        (static_cast<std::size_t>(grid.y(i) + r) * static_cast<std::size_t>(frame_width)) * 4 + x;
    std::memcpy(frame.data() + dst, tile.data() + static_cast<std::size_t>(r) * row_bytes,
                row_bytes);
  }
}

std::string format_cost(double s) {
  if (s < 1e-6) return fmt::format("{:.3g} ns", s * 1e9);
  if (s < 1e-3) return fmt::format("{:.3g} us", s * 1e6);
  if (s < 1.0) return fmt::format("{:.3g} ms", s * 1e3);
  return fmt::format("{:.3g} s", s);
}

}  // namespace fixstep::cli
