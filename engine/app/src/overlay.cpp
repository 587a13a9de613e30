// app::Overlay (overlay.hpp): the HUD lines kept between frames, and the frame being drawn.
#include "fixstep/app/overlay.hpp"

#include "fixstep/app/session.hpp"

namespace fixstep::app {

void Overlay::text(std::string_view line) {
  if (line_count_ == lines_.size()) lines_.emplace_back();
  lines_[line_count_++].assign(line);  // the kept string's storage, when large enough
}

void Overlay::clear() {
  DrawList::clear();
  line_count_ = 0;
}

std::optional<Vec2> Overlay::position(Entity body) const {
  return session_ ? session_->drawn_position(body) : std::nullopt;
}

const World* Overlay::world() const {
  return session_ ? &session_->simulation() : nullptr;
}

Camera Overlay::camera() const {
  return session_ ? session_->view() : Camera{};
}

int Overlay::width() const {
  return session_ ? session_->renderer().width() : 0;
}

int Overlay::height() const {
  return session_ ? session_->renderer().height() : 0;
}

Vec2 Overlay::to_screen(Vec2 p) const {
  if (!session_) return {};
  const std::array<double, 2> q = session_->renderer().to_pixel(p.x, p.y);
  return {q[0], q[1]};
}

}  // namespace fixstep::app
