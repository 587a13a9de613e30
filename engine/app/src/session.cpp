#include "fixstep/session.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string_view>
#include <utility>
#include <vector>

#include "fixstep/detail/defined_entity.hpp"
#include "fixstep/stability.hpp"

namespace fixstep {

namespace {
/// With planes, bodies bounce: a collider body under gravity g rises at most |v|²/(2|g|)
/// above its start along -g (its kinetic energy all turned into height; restitution <= 1 never
/// adds energy), so that point is included; then the point of each plane nearest the box's
/// centre, so the ground and walls the bodies bounce between are in view.
template <class Include>
void include_bounces(const WorldDef& def, Include&& include, double& x0, double& x1, double& y0,
                     double& y1) {
  for (const BodyDef& b : def.bodies) {
    if (!b.collider || !b.gravity) continue;
    const Vec2 g = b.gravity->acceleration;
    const double gn = std::hypot(g.x, g.y);
    if (!(gn > 0.0)) continue;
    const Vec2 v = b.body.velocity, p = b.body.position;
    const double rise = (v.x * v.x + v.y * v.y) / (2.0 * gn);
    include(p.x - g.x / gn * rise, p.y - g.y / gn * rise, b.collider->radius);
  }
  if (!(x0 <= x1)) return;  // no bodies
  const double cx = 0.5 * (x0 + x1), cy = 0.5 * (y0 + y1);
  for (const PlaneDef& p : def.planes) {
    const double len = std::hypot(p.normal.x, p.normal.y);
    if (!(len > 0.0)) continue;
    const double nx = p.normal.x / len, ny = p.normal.y / len;
    const double gap = nx * cx + ny * cy - p.offset;
    include(cx - gap * nx, cy - gap * ny, 0.0);
  }
}
}  // namespace

Camera fit_camera(const WorldDef& def, int width, int height) {
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
  auto include = [&](double x, double y, double r) {
    x0 = std::min(x0, x - r), x1 = std::max(x1, x + r);
    y0 = std::min(y0, y - r), y1 = std::max(y1, y + r);
  };
  for (const BodyDef& b : def.bodies) {
    include(b.body.position.x, b.body.position.y, b.appearance ? b.appearance->radius : 0.0);
    if (b.spring) {
      const auto& s = *b.spring;
      const double dx = b.body.position.x - s.anchor.x, dy = b.body.position.y - s.anchor.y;
      const double omega = std::sqrt(s.stiffness / b.body.mass);
      const double speed = std::hypot(b.body.velocity.x, b.body.velocity.y);
      const double reach = std::hypot(dx, dy) + s.rest_length + (omega > 0 ? speed / omega : 0);
      include(s.anchor.x, s.anchor.y, reach);
    }
  }
  // Bodies held at one anchor through links (a rope pinned at one end) may swing all the way
  // round it: include the circle through the farthest body of each such group. Groups held at
  // two or more anchors (a cloth) keep to their bodies' box.
  if (!def.links.empty()) {
    const std::size_t n = def.bodies.size();
    std::vector<std::size_t> group(n);
    std::iota(group.begin(), group.end(), std::size_t{0});
    auto root = [&](std::size_t i) {
      while (group[i] != i) i = group[i] = group[group[i]];
      return i;
    };
    for (const detail::IndexLink& l : detail::index_links(def.links, n)) {
      group[root(l.body_a)] = root(l.body_b);
    }
    std::vector<std::size_t> anchors(n, 0), held_by(n, 0);
    for (std::size_t i = 0; i < n; ++i) {
      if (def.bodies[i].spring) ++anchors[root(i)], held_by[root(i)] = i;
    }
    std::vector<double> reach(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t g = root(i);
      if (anchors[g] != 1) continue;
      const Vec2 a = def.bodies[held_by[g]].spring->anchor, p = def.bodies[i].body.position;
      reach[g] = std::max(reach[g], std::hypot(p.x - a.x, p.y - a.y));
    }
    for (std::size_t g = 0; g < n; ++g) {
      if (anchors[g] == 1 && group[g] == g) {
        const Vec2 a = def.bodies[held_by[g]].spring->anchor;
        include(a.x, a.y, reach[g]);
      }
    }
  }
  if (!def.planes.empty()) include_bounces(def, include, x0, x1, y0, y1);
  const double aspect = double(width) / double(height);
  Camera c;
  c.center = {0.5 * (x0 + x1), 0.5 * (y0 + y1)};
  c.width = std::max({(x1 - x0), (y1 - y0) * aspect, 1.0}) * 1.15;
  return c;
}

namespace {
std::vector<std::string_view> split_words(std::string_view s) {
  std::vector<std::string_view> words;
  std::size_t i = 0;
  while (i < s.size()) {
    const std::size_t j = s.find(' ', i);
    const std::size_t end = j == std::string_view::npos ? s.size() : j;
    if (end > i) words.push_back(s.substr(i, end - i));
    i = end + 1;
  }
  return words;
}
/// The HUD lines for the runtime guard's message: a heading, then the message wrapped at about
/// 100 characters, with the Greek letters spelled out (the bitmap font is ASCII only).
std::vector<std::string> fault_hud_lines(std::string message) {
  for (const auto& [from, to] :
       {std::pair<std::string_view, std::string_view>{"ω", "omega"}, {"γ", "gamma"}, {"·", "*"}}) {
    for (std::size_t at = message.find(from); at != std::string::npos;
         at = message.find(from, at)) {
      message.replace(at, from.size(), to);
    }
  }
  std::vector<std::string> lines{"STOPPED: the state left the finite range"};
  std::string line;
  for (const std::string_view word : split_words(message)) {
    if (!line.empty() && line.size() + word.size() + 1 > 100)
      lines.push_back(std::move(line)), line.clear();
    if (!line.empty()) line += ' ';
    line += word;
  }
  if (!line.empty()) lines.push_back(std::move(line));
  return lines;
}

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
  follow_named();
}

void Session::draw() {
  fill_render_frame(*sim_, loop_.alpha(), frame_);
  if (!follow_.is_null()) {
    if (sim_->contains(follow_)) {
      const std::size_t j = sim_->index_of(follow_);
      renderer_.set_camera(
          Camera{.center = {frame_.x[j], frame_.y[j]}, .width = renderer_.camera().width});
    } else {
      follow_ = null_entity;  // destroyed: the view stays where it was
    }
  }
  if (sim_->contains(drag_body_)) {
    frame_.springs.push_back({static_cast<float>(drag_pointer_.x),
                              static_cast<float>(drag_pointer_.y),
                              static_cast<std::uint32_t>(sim_->index_of(drag_body_))});
  }
  hud_.clear();
  if (show_engine_hud_) engine_hud_lines();
  if (const auto& fault = sim_->fault()) {
    // Built once: the guard's message (which runs the stability analysis) does not change
    // while the simulation stays stopped.
    if (fault_lines_.empty())
      fault_lines_ = fault_hud_lines(explain_fault(def_.bodies, def_.links, def_.settings, *fault));
    hud_.insert(hud_.end(), fault_lines_.begin(), fault_lines_.end());
  }
  if (show_controls_ && show_engine_hud_) control_hud_lines();
  hud_.insert(hud_.end(), status_lines_.begin(), status_lines_.end());
  reserve_hud(hud_.size());
  renderer_.draw(frame_, hud_);
}

void Session::engine_hud_lines() {
  const std::size_t n = sim_->body_count();
  hud_.push_back(fmt::format("fixstep  {}{}({} bod{})", title_, title_.empty() ? "" : "  ", n,
                             n == 1 ? "y" : "ies"));
  const int substeps = sim_->settings().substeps;
  hud_.push_back(fmt::format("tick {}   t = {:.3f} s   dt = {:g} s{}", sim_->tick(), sim_->time(),
                             sim_->settings().dt,
                             substeps > 1 ? fmt::format(" ({} substeps)", substeps) : ""));
  hud_.push_back(fmt::format("{} ({})", integrator_name(sim_->settings().integrator),
                             precision_name(sim_->precision())));
  if (show_energy_) {
    const double balance = energy_balance(*sim_, initial_energy_);
    hud_.push_back(fmt::format("energy {:.6g} J   dissipated {:.6g} J   balance {:+.3g}{}",
                               sim_->energy().total(), sim_->dissipated_energy(),
                               initial_energy_ != 0.0 ? 100.0 * balance : balance,
                               initial_energy_ != 0.0 ? " %" : " J"));
  }
}

void Session::control_hud_lines() {
  hud_.push_back(
      fmt::format("time x{:g}{}", loop_.time_scale(), loop_.paused() ? "   PAUSED" : ""));
  hud_.push_back(key_help_);
}

// The HUD's lines (engine_hud_lines, control_hud_lines): title, tick, integrator, the energy
// line when shown; the loop's state and the key help.
std::size_t Session::planned_hud_lines() const {
  std::size_t n = status_lines_.size();
  if (show_engine_hud_) n += (show_energy_ ? 4 : 3) + (show_controls_ ? 2 : 0);
  return n;
}

void Session::reserve_hud(std::size_t lines) {
  if (!auto_view_ || lines <= hud_reserved_) return;
  hud_reserved_ = lines;
  // The HUD panel covers a band at the top of the frame (at most half of it): the world is
  // fitted into the part below, as `fixstep compare` fits its tiles.
  const int w = renderer_.width(), h = renderer_.height();
  const float panel = Renderer::hud_height(lines, renderer_.hud_text_scale());
  const int band = std::min(static_cast<int>(std::ceil(panel)), h / 2);
  const Camera fit = fit_camera(def_, w, h - band);
  const double width = auto_width_.value_or(fit.width);
  renderer_.set_camera(
      Camera{.center = {fit.center.x, fit.center.y + 0.5 * band * width / w}, .width = width});
}

void Session::set_show_controls(bool show) {
  show_controls_ = show;
  reserve_hud(planned_hud_lines());
}

void Session::set_show_energy(bool show) {
  show_energy_ = show;
  reserve_hud(planned_hud_lines());
}

void Session::set_show_engine_hud(bool show) {
  show_engine_hud_ = show;
  reserve_hud(planned_hud_lines());
}

void Session::set_status_lines(std::vector<std::string> lines) {
  status_lines_ = std::move(lines);
  reserve_hud(planned_hud_lines());
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
