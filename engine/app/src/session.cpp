#include "fixstep/app/session.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string_view>
#include <utility>
#include <vector>

#include "fixstep/core/defined_bodies.hpp"
#include "fixstep/core/input.hpp"
#include "fixstep/core/stability.hpp"
#include "fixstep/core/world_def.hpp"
#include "fixstep/core/world_settings.hpp"

namespace fixstep {

namespace {

/// The HUD and summaries show the energy balance, so the dissipation account is kept.
const WorldDef& tracked(WorldDef& def) {
  def.settings.track_dissipation = true;
  return def;
}

/// The loop of dt with the frame-time clamp max_frame_time and a tick cap that never binds
/// below it (the derived cap stops at 10^6 + 1 ticks).
FixedStepLoop make_loop(double dt, double max_frame_time) {
  const double ticks = std::ceil(max_frame_time / dt) + 1.0;
  if (!(ticks <= max_frame_ticks)) {
    throw std::invalid_argument(fmt::format(
        "Session: a frame of {} s is more than 2^30 ticks of dt = {} s", max_frame_time, dt));
  }
  return FixedStepLoop(dt, LoopSettings{.max_frame_time = max_frame_time,
                                        .max_ticks_per_frame = static_cast<int>(ticks)});
}

/// `sim`, checked to be a fresh build of `def` (Session's second constructor).
World& built(World& sim, const WorldDef& def) {
  if (sim.tick() != 0 || sim.body_count() != def.bodies.size() ||
      !sim.settings().track_dissipation) {
    throw std::invalid_argument(fmt::format(
        "Session: the simulation given is not a fresh build of its definition (tick {}, {} of "
        "{} bodies, dissipation {}tracked)",
        sim.tick(), sim.body_count(), def.bodies.size(),
        sim.settings().track_dissipation ? "" : "not "));
  }
  return sim;
}

}  // namespace

Session::Session(WorldDef def, const SessionSettings& settings)
    : def_(std::move(def)),
      title_(settings.title),
      sim_(std::make_unique<World>(World(tracked(def_)))),
      loop_(make_loop(def_.settings.dt, settings.max_frame_time)),
      renderer_(settings.width, settings.height) {
  start(settings);
}

Session::Session(WorldDef def, World sim, const SessionSettings& settings)
    : def_(std::move(def)),
      title_(settings.title),
      sim_(std::make_unique<World>(std::move(built(sim, tracked(def_))))),
      loop_(make_loop(def_.settings.dt, settings.max_frame_time)),
      renderer_(settings.width, settings.height) {
  start(settings);
}

void Session::start(const SessionSettings& settings) {
  sim_->set_keep_previous(true);
  initial_energy_ = sim_->energy().total();
  Camera camera = fit_camera(def_, settings.width, settings.height);
  if (settings.view_center) camera.center = *settings.view_center;
  if (settings.view_width) camera.width = *settings.view_width;
  renderer_.set_camera(camera);
  renderer_.set_hud_text_scale(settings.hud_text_scale);
  renderer_.set_view_style(settings.style);
  renderer_.set_hud_corner(settings.hud_corner);
  hud_corner_ = settings.hud_corner;
  show_hud_ = settings.show_hud;
  hud_lines_ = settings.hud_lines & all_hud_lines;
  auto_view_ = !settings.view_center;
  auto_width_ = settings.view_width;
  reserve_hud(planned_hud_lines());
  follow_name_ = settings.follow;
  follow_named();
}

void Session::follow_named() {
  if (follow_name_.empty()) return;
  const Entity body = sim_->find(follow_name_);
  if (body.is_null()) {
    throw std::invalid_argument(fmt::format(
        "Session: the view is to follow \"{}\", and no body has that name", follow_name_));
  }
  follow(body);
}

FrameResult Session::advance(double frame_seconds, const TickInput& input) {
  // After the runtime guard fires, no further tick runs and the loop pauses: the state stays
  // at the tick that diverged, and draw() shows why.
  return advance_with(frame_seconds, [&](std::uint64_t t, World& sim) {
    TickInput in = input;
    in.tick = t;
    sim.step(in);
  });
}

FrameResult Session::advance(double frame_seconds, InputSampler& sampler) {
  return advance_with(frame_seconds,
                      [&](std::uint64_t t, World& sim) { sim.step(sampler.sample(t)); });
}

void Session::pause_on_fault() {
  if (sim_->fault()) loop_.set_paused(true);
}

void Session::save(Snapshot& out) const {
  sim_->save(out.world);
  out.loop = loop_.state();
}

void Session::restore(const WorldSnapshot& world) {
  sim_->restore(world);
  loop_.restore({0.0, world.tick()});
  fault_lines_.clear();
  renderer_.clear_trails();
  frame_ready_ = false;
}

void Session::restore(const Snapshot& snapshot) {
  restore(snapshot.world);
  loop_.restore(snapshot.loop);  // the saved accumulator, not an empty one
}

void Session::restart() {
  sim_ = std::make_unique<World>(World(def_));
  sim_->set_keep_previous(true);
  fault_lines_.clear();
  loop_.reset();
  renderer_.clear_trails();
  frame_ready_ = false;
  follow_named();
}

void Session::set_view(Vec2 center, double width) {
  if (!std::isfinite(center.x) || !std::isfinite(center.y))
    throw std::invalid_argument(fmt::format(
        "Session::set_view: center must be finite, got ({}, {}) m", center.x, center.y));
  if (!(std::isfinite(width) && width > 0.0))
    throw std::invalid_argument(
        fmt::format("Session::set_view: width must be finite and > 0, got {} m", width));
  take_view();
  follow_ = null_entity;
  renderer_.set_camera(Camera{.center = center, .width = width});
}

void Session::follow(Entity body) {
  if (!body.is_null() && !sim_->contains(body))
    throw std::invalid_argument(fmt::format(
        "Session::follow: no body has handle (slot {}, generation {}) (destroyed or from "
        "another world)",
        body.slot(), body.generation));
  take_view();
  follow_ = body;
}

void Session::zoom(double factor) {
  const double width = renderer_.camera().width / factor;
  if (!(std::isfinite(factor) && factor > 0.0) || !(std::isfinite(width) && width > 0.0))
    throw std::invalid_argument(fmt::format(
        "Session::zoom: factor must be finite and > 0 and leave a finite width, got {} (width "
        "{} m)",
        factor, renderer_.camera().width));
  take_view();
  renderer_.set_camera(Camera{.center = renderer_.camera().center, .width = width});
}

}  // namespace fixstep
