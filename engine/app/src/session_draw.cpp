// Session's drawing (session.hpp): the frame taken at alpha, the game's overlay, the HUD's lines,
// corner and band, and the view style.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string_view>
#include <utility>
#include <vector>

#include "fixstep/app/session.hpp"
#include "fixstep/core/stability.hpp"
#include "fixstep/core/step_results.hpp"
#include "fixstep/core/world_settings.hpp"
#include "fixstep/render/hud_layout.hpp"

namespace fixstep {

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

}  // namespace

void Session::after_tick() {
  renderer_.sample_trails(*sim_);
  frame_ready_ = false;
}

void Session::prepare_frame() {
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
  frame_ready_ = true;
}

std::optional<Vec2> Session::drawn_position(Entity body) const {
  if (!frame_ready_ || !sim_->contains(body)) return std::nullopt;
  const std::size_t j = sim_->index_of(body);
  if (j >= frame_.x.size()) return std::nullopt;
  return Vec2{frame_.x[j], frame_.y[j]};
}

void Session::draw() {
  render(nullptr);
}

void Session::draw(const DrawList& overlay) {
  render(&overlay);
}

void Session::render(const DrawList* overlay) {
  if (!frame_ready_) prepare_frame();
  frame_ready_ = false;
  hud_.clear();
  if (show_hud_ && show_engine_hud_) engine_hud_lines();
  if (const auto& fault = sim_->fault()) {
    // Built once: the guard's message (which runs the stability analysis) does not change
    // while the simulation stays stopped.
    if (fault_lines_.empty())
      fault_lines_ = fault_hud_lines(explain_fault(def_.bodies, def_.links, def_.settings, *fault));
    hud_.insert(hud_.end(), fault_lines_.begin(), fault_lines_.end());
  }
  if (show_hud_ && show_engine_hud_ && show_controls_ && (hud_lines_ & hud_controls) != 0)
    control_hud_lines();
  if (show_hud_) {
    hud_.insert(hud_.end(), status_lines_.begin(),
                status_lines_.begin() + static_cast<std::ptrdiff_t>(status_count_));
  }
  // The band kept free of the world holds the lines as drawn, wrapped to the frame's width.
  if (auto_view_ && show_hud_) {
    reserve_hud(std::max(hud_.size(), layout_hud(hud_, renderer_.hud_text_scale(), hud_corner_,
                                                 renderer_.width(), renderer_.height())
                                          .lines.size()));
  }
  renderer_.draw_scene(frame_);
  if (overlay != nullptr) overlay->draw(renderer_);
  renderer_.draw_hud(hud_);
  renderer_.finish();
}

void Session::engine_hud_lines() {
  const std::size_t n = sim_->body_count();
  if ((hud_lines_ & hud_title) != 0) {
    hud_.push_back(fmt::format("fixstep  {}{}({} bod{})", title_, title_.empty() ? "" : "  ", n,
                               n == 1 ? "y" : "ies"));
  }
  const int substeps = sim_->settings().substeps;
  if ((hud_lines_ & hud_time) != 0) {
    hud_.push_back(fmt::format("tick {}   t = {:.3f} s   dt = {:g} s{}", sim_->tick(), sim_->time(),
                               sim_->settings().dt,
                               substeps > 1 ? fmt::format(" ({} substeps)", substeps) : ""));
  }
  if ((hud_lines_ & hud_integrator) != 0) {
    hud_.push_back(fmt::format("{} ({})", integrator_name(sim_->settings().integrator),
                               precision_name(sim_->precision())));
  }
  if (show_energy_ && (hud_lines_ & hud_energy) != 0) {
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
  if (!show_hud_) return 0;
  std::size_t n = status_count_;
  if (show_engine_hud_) {
    for (const unsigned bit : {hud_title, hud_time, hud_integrator}) n += (hud_lines_ & bit) != 0;
    n += show_energy_ && (hud_lines_ & hud_energy) != 0;
    n += show_controls_ && (hud_lines_ & hud_controls) != 0 ? 2 : 0;
  }
  return n;
}

void Session::reserve_hud(std::size_t lines) {
  if (!auto_view_ || !show_hud_ || lines <= hud_reserved_) return;
  hud_reserved_ = lines;
  // The HUD panel covers a band at the top (or the bottom) of the frame (at most half of it):
  // the world is fitted into the rest, as `fixstep compare` fits its tiles.
  const int w = renderer_.width(), h = renderer_.height();
  const float panel = Renderer::hud_height(lines, renderer_.hud_text_scale());
  const int band = std::min(static_cast<int>(std::ceil(panel)), h / 2);
  const Camera fit = fit_camera(def_, w, h - band);
  const double width = auto_width_.value_or(fit.width);
  const bool bottom =
      hud_corner_ == HudCorner::bottom_left || hud_corner_ == HudCorner::bottom_right;
  const double shift = 0.5 * band * width / w;  // m: the fit's centre moves away from the band
  renderer_.set_camera(
      Camera{.center = {fit.center.x, fit.center.y + (bottom ? -shift : shift)}, .width = width});
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

void Session::set_status_lines(std::span<const std::string> lines) {
  if (status_lines_.size() < lines.size()) status_lines_.resize(lines.size());
  for (std::size_t i = 0; i < lines.size(); ++i) status_lines_[i].assign(lines[i]);
  status_count_ = lines.size();
  reserve_hud(planned_hud_lines());
}

void Session::set_hud_corner(HudCorner corner) {
  if (corner == hud_corner_) return;
  hud_corner_ = corner;
  renderer_.set_hud_corner(corner);
  const std::size_t reserved = hud_reserved_;
  hud_reserved_ = 0;  // the band moves to the other edge
  reserve_hud(std::max(reserved, planned_hud_lines()));
}

void Session::set_show_hud(bool show) {
  show_hud_ = show;
  reserve_hud(planned_hud_lines());
}

void Session::set_hud_lines(unsigned lines) {
  hud_lines_ = lines & all_hud_lines;
  reserve_hud(planned_hud_lines());
}

void Session::set_hud_text_scale(float scale) {
  renderer_.set_hud_text_scale(scale);
  const std::size_t reserved = hud_reserved_;
  hud_reserved_ = 0;  // the band's height changes
  reserve_hud(std::max(reserved, planned_hud_lines()));
}

}  // namespace fixstep
