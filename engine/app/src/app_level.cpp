// fixstep::app: the level a run starts from (fixstep/app/game_level.hpp).
#include <any>
#include <cstdio>
#include <fixstep/app/scene_view_settings.hpp>
#include <fixstep/core/input.hpp>
#include <fixstep/core/world_settings.hpp>
#include <fixstep/scene/scene.hpp>
#include <memory>
#include <stdexcept>

#include "fixstep/app/game_level.hpp"

namespace fixstep::app::detail {

namespace {

/// The view: the settings', else the scene's [view], else the automatic one; its look likewise.
SessionSettings view(const Settings& settings, const SceneView& scene_view) {
  SessionSettings s{.width = settings.width,
                    .height = settings.height,
                    .title = settings.name,
                    .view_center = settings.view_center ? settings.view_center : scene_view.center,
                    .view_width = settings.view_width ? settings.view_width : scene_view.width,
                    .follow = settings.follow};
  apply_scene_view_style(scene_view, s);
  if (settings.style) s.style = *settings.style;
  if (settings.hud_corner) s.hud_corner = *settings.hud_corner;
  if (settings.show_hud) s.show_hud = *settings.show_hud;
  if (settings.hud_text_scale) s.hud_text_scale = *settings.hud_text_scale;
  if (settings.hud_lines) s.hud_lines = *settings.hud_lines;
  return s;
}

Level from_scene(const AnyGame& game, const Settings& settings, const Scene* scene) {
  Level level;
  if (scene != nullptr) {
    for (const std::string& w : scene->warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
    level.def = scene->def;
    level.scene_name = scene->file;
    level.scene_text = scene->text;
  } else {
    level.scene_name = settings.name + " (built in code)";
  }
  level.view = view(settings, scene != nullptr ? scene->view : SceneView{});
  std::unique_ptr<AnyGame> set_up = game.clone();
  set_up->setup(level.def);
  level.game = std::move(set_up);
  // Summaries print the energy balance, and a Session keeps the account anyway: every mode
  // steps the same world.
  level.def.settings.track_dissipation = true;
  return level;
}

}  // namespace

Level load_level(const AnyGame& game, const Settings& settings, const std::string& file) {
  if (file.empty()) return from_scene(game, settings, nullptr);
  const Scene scene = load_scene(file);  // throws SceneError naming file:line:column and key
  return from_scene(game, settings, &scene);
}

Level replay_level(const AnyGame& game, const Settings& settings, const Recording& rec,
                   const std::optional<std::string>& scene) {
  Level level;
  if (!scene && !rec.scene_text.empty()) {
    const Scene carried = parse_scene(rec.scene_text, rec.scene);
    level = from_scene(game, settings, &carried);
  } else {
    level = load_level(game, settings, scene.value_or(settings.scene_file));
  }
  apply_settings(level.def, rec.settings);  // the recorded dt, integrator, precision, substeps
  level.def.allow_unstable = true;  // the recorded run ran: World(def) checks its limits only
  return level;
}

InputMap game_input_map(const Settings& settings) {
  InputMap map{settings.actions.empty() ? default_actions() : settings.actions, settings.axes,
               settings.loop_keys};
  if (const auto problem = map.problem()) {
    throw std::invalid_argument("Settings: " + *problem);
  }
  return map;
}

ScriptNames script_names(const InputMap& map) {
  ScriptNames names;
  for (const ActionBinding& a : map.actions) names.actions.emplace_back(a.name, a.bit);
  for (const AxisBinding& a : map.axes) names.axes.emplace_back(a.name, a.index);
  return names;
}

TickRules game_rules(AnyGame& game, bool before_step) {
  TickRules rules;
  rules.save = [&game] { return std::any(std::shared_ptr<const AnyGame>(game.clone())); };
  rules.restore = [&game](const std::any& saved) {
    game.assign(*std::any_cast<const std::shared_ptr<const AnyGame>&>(saved));
  };
  auto run = [&game](World& world, const TickInput& input) { game.rules(world, input); };
  rules.attach = [&game](World& world) { game.attach(world); };
  (before_step ? rules.before_tick : rules.after_tick) = run;
  return rules;
}

}  // namespace fixstep::app::detail
