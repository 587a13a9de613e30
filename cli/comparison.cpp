// Comparison: the tiles of `fixstep compare`, each stepping its own world from the same scene on
// the same clock, and what each HUD shows of its cost and how far it strays.
#include "comparison.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fixstep/app/session.hpp>
#include <fixstep/core/components.hpp>
#include <fixstep/core/input.hpp>
#include <fixstep/core/limits.hpp>
#include <fixstep/core/step_results.hpp>
#include <fixstep/core/world_def.hpp>
#include <fixstep/core/world_settings.hpp>
#include <fixstep/scene/scene_stability.hpp>
#include <memory>
#include <stdexcept>
#include <string>

#include "commands.hpp"
#include "compare_tiles.hpp"
#include "exact_reference.hpp"
#include "fixstep/io/command_limits.hpp"
#include "progress.hpp"
#include "step_cost.hpp"

namespace fixstep::cli {
namespace {

// The reference tile's error line: the widest HUD line but the label.
constexpr const char* reference_line = "reference: the most accurate";

std::string hud_label(std::size_t index, const std::string& label) {
  return fmt::format("{}  {}", index + 1, label);
}

// The HUD's text scale for every tile: the largest of 2, 1.75, ... 1 px per font pixel at which
// the widest label and the reference line fit a tile `width` px wide with 4 px to spare.
float hud_text_scale(std::span<const std::string> labels, int width) {
  std::string widest = reference_line;
  for (const std::string& l : labels)
    if (Renderer::text_width(l, 1.0f) > Renderer::text_width(widest, 1.0f)) widest = l;
  float scale = 2.0f;
  while (scale > 1.0f && Renderer::hud_width(widest, scale) > float(width - 4)) scale -= 0.25f;
  return scale;
}

}  // namespace

Comparison::Comparison(const Scene& base, std::span<const TileSpec> specs, const TileGrid& grid,
                       bool quiet, double max_frame_time)
    : base_(base), exact_(base_), grid_(grid), max_frame_time_(max_frame_time) {
  std::vector<Scene> scenes;
  std::vector<World> worlds;  // World(def) of each tile: checked once, here
  for (std::size_t i = 0; i < specs.size(); ++i) {
    scenes.push_back(tile_scene(base_, specs[i]));
    try {  // before the guard: a tile may ask for more work per tick than the scene (limits.hpp)
      check_world_limits(scenes.back().def.bodies, scenes.back().def.links,
                         scenes.back().def.planes, scenes.back().def.settings);
    } catch (const LimitError& e) {
      throw LimitError(fmt::format("--with '{}': {}", specs[i].text, e.what()));
    }
    // Before a Session refuses it: a dt too short for a frame, named by its --with.
    const double dt = scenes.back().def.settings.dt;
    const std::optional<double> fps = max_frame_time_ > SessionSettings{}.max_frame_time
                                          ? std::optional(1.0 / max_frame_time_)
                                          : std::nullopt;
    check_frame_ticks(
        max_frame_time_, dt, fps,
        specs[i].dt
            ? fmt::format("--with '{}'", specs[i].text)
            : fmt::format("--with '{}' (the scene's [world] dt = {:g} s)", specs[i].text, dt),
        fmt::format("give --with '{}@DT' a DT of", integrator_name(specs[i].integrator)));
    try {
      const WorkProgressLine shown(!quiet);  // seconds on a network of 10^6 bodies
      worlds.emplace_back(scenes.back().def);
    } catch (const UnstableDefinition& e) {
      throw std::invalid_argument(fmt::format(
          "--with '{}' is unstable on this scene: add the substeps the guard names "
          "(--with '{}:substeps=N') or pass --allow-unstable to watch it diverge. The guard: {}",
          specs[i].text, specs[i].text, located(scenes.back(), e).what()));
    }
    for (const std::string& w : located_warnings(scenes.back(), worlds.back().warnings())) {
      if (!quiet)
        std::fprintf(stderr, "warning: --with '%s': %s\n", specs[i].text.c_str(), w.c_str());
    }
  }
  reference_ = most_accurate(scenes);
  std::vector<std::string> labels;
  for (std::size_t i = 0; i < specs.size(); ++i)
    labels.push_back(hud_label(i, tile_label(specs[i], scenes[i])));
  // With disc contacts an error line may say how many bodies a contact has touched, or that
  // it has touched them all (hud()): the widest of each fits too.
  std::vector<std::string> widest = labels;
  if (base_.def.settings.contacts) {
    widest.push_back(
        fmt::format("error 1.23e-14 m vs exact ({} touched)", base_.def.bodies.size()));
    widest.push_back(fmt::format("no exact: contact at tick {}", max_command_ticks));
  }
  hud_scale_ = hud_text_scale(widest, grid_.tile_width);
  for (std::size_t i = 0; i < specs.size(); ++i) {
    auto tile = std::make_unique<Tile>();
    tile->spec = specs[i];
    tile->scene = std::move(scenes[i]);
    tile->label = labels[i];
    tile->cost = step_cost(worlds[i]);
    tile->session = std::make_unique<Session>(tile->scene.def, std::move(worlds[i]),
                                              tile_settings(tile->scene));
    tile->session->set_show_engine_hud(false);
    tile->touched.emplace(tile->scene);
    tiles_.push_back(std::move(tile));
  }
  {
    const World& sim0 = tiles_.front()->session->simulation();
    has_exact_ = exact_error(exact_, sim0).has_value();
  }
  start();
}

SessionSettings Comparison::tile_settings(const Scene& scene) const {
  const int w = grid_.tile_width, h = grid_.tile_height;
  SessionSettings s = session_settings(scene, w, h);
  s.hud_text_scale = hud_scale_;
  s.hud_corner = HudCorner::top_left;  // the tiles' own HUD layout: the band below is for it
  s.show_hud = true;
  s.max_frame_time = max_frame_time_;
  // The HUD covers the tile's top band: the scene is fitted into the part below it.
  const int band =
      std::min(int(std::ceil(Renderer::hud_height(hud_lines, s.hud_text_scale))), h / 2);
  const Camera fit = fit_camera(scene.def, w, h - band);
  const double width = scene.view.width ? *scene.view.width * h / (h - band) : fit.width;
  const Vec2 center = scene.view.center.value_or(fit.center);
  s.view_width = width;
  s.view_center = Vec2{center.x, center.y + 0.5 * band * width / w};  // m: y up, band at the top
  return s;
}

void Comparison::restart() {
  for (const auto& t : tiles_) t->session->restart();
  start();
}

void Comparison::start() {
  for (std::size_t i = 0; i < tiles_.size(); ++i) {
    Tile& t = *tiles_[i];
    t.wall_seconds = 0.0;
    t.error.reset();
    t.error_time = 0.0;
    t.max_error = 0.0;
    t.touched->clear();
    t.shadow.reset();
    if (!has_exact_ && i != reference_) {
      // The reference tile's world at tick 0 (sessions restart before this loop), copied.
      t.shadow = std::make_unique<World>(tiles_[reference_]->session->simulation());
      t.shadow->set_keep_previous(false);  // never drawn
    }
    measure(i);
  }
}

void Comparison::advance(double seconds) {
  for (std::size_t i = 0; i < tiles_.size(); ++i) {
    Tile& t = *tiles_[i];
    const auto start = std::chrono::steady_clock::now();
    // As Session::advance, with each tick's contacts noted for the exact error.
    t.session->advance_with(seconds, [&](std::uint64_t tick, World& sim) {
      sim.step(TickInput{.tick = tick});
      if (has_exact_) t.touched->after_tick(sim);
    });
    t.wall_seconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    measure(i);
  }
}

void Comparison::measure(std::size_t i) {
  Tile& t = *tiles_[i];
  const World& sim = t.session->simulation();
  if (sim.fault()) return;  // the last measurement stands; the HUD shows the guard's message
  std::optional<double> e;
  if (has_exact_) {
    e = exact_error(exact_, sim, &*t.touched);
    if (!e) t.error.reset();  // every body touched by a contact: no exact error from now on
  } else if (t.shadow) {
    e = against_shadow(sim, *t.shadow);
  }
  if (!e) return;
  t.error = e;
  t.error_time = sim.time();
  t.max_error = std::max(t.max_error, *e);
}

std::optional<double> Comparison::against_shadow(const World& sim, World& shadow) {
  // The reference configuration, stepped up to this tile's time: it lands on it when the time is
  // on both tiles' grids of ticks (every 1/15 s for steps of 1/60, 1/30 and 1/15 s).
  const double t = sim.time(), tolerance = 1e-9 * std::max(1.0, t);
  const double dt = shadow.settings().dt;
  while (!shadow.fault() && static_cast<double>(shadow.tick() + 1) * dt <= t + tolerance) {
    shadow.step();
  }
  if (shadow.fault() || std::abs(shadow.time() - t) > tolerance) return std::nullopt;
  double worst = 0.0;
  for (std::size_t j = 0; j < sim.body_count(); ++j) {
    const Body a = sim.body(sim.bodies()[j]), b = shadow.body(shadow.bodies()[j]);
    worst = std::max(worst, std::hypot(a.position.x - b.position.x, a.position.y - b.position.y));
  }
  return worst;
}

std::string Comparison::error_against(std::size_t i) const {
  if (has_exact_) {
    const TouchedBodies& touched = *tiles_[i]->touched;
    const std::size_t n = tiles_[i]->session->simulation().body_count();
    return touched.first()
               ? fmt::format("exact ({} of {} bodies touched by a contact)", touched.count(), n)
               : "exact";
  }
  return i == reference_ ? "" : fmt::format("tile {}", reference_ + 1);
}

std::string Comparison::exact_lost(std::size_t i) const {
  const Tile& t = *tiles_[i];
  if (!has_exact_ || t.error || !t.touched->first()) return {};
  return fmt::format("disc contact at tick {}", *t.touched->first());
}

std::vector<std::string> Comparison::hud(std::size_t i) const {
  const Tile& t = *tiles_[i];
  const World& sim = t.session->simulation();
  std::vector<std::string> lines;
  lines.reserve(hud_lines);
  lines.push_back(t.label);
  lines.push_back(fmt::format("t = {:.3f} s   tick {}", sim.time(), sim.tick()));
  if (!has_exact_ && i == reference_) {
    lines.emplace_back(reference_line);
  } else if (t.error) {
    const std::size_t touched = t.touched->count();
    lines.push_back(
        has_exact_
            ? fmt::format("error {:.3g} m vs exact{}", *t.error,
                          touched > 0 ? fmt::format(" ({} touched)", touched) : std::string())
            : fmt::format("error {:.3g} m vs tile {}", *t.error, reference_ + 1));
  } else if (!exact_lost(i).empty()) {
    lines.push_back(fmt::format("no exact: contact at tick {}", *t.touched->first()));
  } else {
    lines.emplace_back("error: no common tick yet");
  }
  const double e0 = t.session->initial_energy();
  const double balance = energy_balance(sim, e0);
  lines.push_back(fmt::format("energy balance {:+.3g}{}", e0 != 0.0 ? 100.0 * balance : balance,
                              e0 != 0.0 ? " %" : " J"));
  lines.push_back(fmt::format("cost {} per sim s", format_cost(t.cost)));
  return lines;
}

void Comparison::draw(std::span<std::uint8_t> frame, int frame_width) {
  for (std::size_t i = 0; i < tiles_.size(); ++i) {
    Session& s = *tiles_[i]->session;
    s.set_status_lines(hud(i));
    s.draw();
    blit_tile(s.renderer().pixels(), grid_, i, frame, frame_width);
  }
}

bool Comparison::any_fault() const {
  for (const auto& t : tiles_) {
    if (t->session->simulation().fault()) return true;
  }
  return false;
}

}  // namespace fixstep::cli
