// fixstep::net_app: a match drawn (app_match_view.hpp).
#include "app_match_view.hpp"

#include <fmt/format.h>

#include <cmath>
#include <fixstep/app/game_play.hpp>
#include <fixstep/app/key_bindings.hpp>
#include <fixstep/capture/capture.hpp>
#include <fixstep/core/input.hpp>
#include <fixstep/core/world_settings.hpp>
#include <stdexcept>
#ifdef FIXSTEP_NET_WINDOW
#include <fixstep/window/window.hpp>
#endif

namespace fixstep::net::detail {

struct MatchView::WindowHolder {
#ifdef FIXSTEP_NET_WINDOW
  explicit WindowHolder(const std::string& title, int width, int height)
      : window(title, width, height) {}
  Window window;
  UserEvents events;
#endif
};

MatchView::MatchView(const app::detail::Level& level, const app::Settings& settings,
                     std::string kind)
    : level_(level), settings_(settings), kind_(std::move(kind)) {}

MatchView::~MatchView() = default;

Session& MatchView::session() {
  if (!session_) session_.emplace(level_.def, level_.view);
  return *session_;
}

void MatchView::open_window(const std::string& title) {
#ifdef FIXSTEP_NET_WINDOW
  window_ = std::make_unique<WindowHolder>(title, settings_.width, settings_.height);
  window_->window.set_input_map(app::detail::game_input_map(settings_));  // the game's keys
#else
  (void)title;
  throw std::runtime_error("this build of fixstep has no window (FIXSTEP_BUILD_WINDOW=OFF)");
#endif
}

bool MatchView::poll_window(InputSampler& sampler, app::detail::AnyGame& game, const World& shown,
                            bool bot) {
#ifdef FIXSTEP_NET_WINDOW
  UserEvents& ev = window_->events;
  window_->window.poll(ev);
  if (ev.quit) return false;
  if (bot) return true;
  feed(ev, sampler, session().renderer().camera(), settings_.width, settings_.height);
  game.input(ev, shown, sampler);
  return true;
#else
  (void)sampler, (void)game, (void)shown, (void)bot;
  return false;
#endif
}

std::string MatchView::status(const MatchPeer& match) const {
  const MatchStats& s = match.stats();
  switch (match.state()) {
    case MatchState::connecting:
      return fmt::format("{}: waiting for the other players", kind_);
    case MatchState::playing:
    case MatchState::finished: {
      const std::string who =
          match.slot() < match.players()
              ? fmt::format("player {} of {}", match.slot(), match.players())
              : fmt::format("spectator {} ({} players)", match.slot() - spectator_slot_base,
                            match.players());
      // The kind played (a joiner taking the host's learns it at its accept): a rollback
      // player's window is at least 1 tick, a lockstep player's and a spectator's 0.
      const std::uint16_t window = match.rollback_window();
      const char* kind = window > 0 ? "rollback" : "lockstep";
      const std::string lag =
          window > 0 ? fmt::format("delay {}  window {}  rollbacks {} (longest {})",
                                   match.input_delay(), window, s.rollbacks, s.max_rolled_back)
                     : fmt::format("delay {}", match.input_delay());
      return fmt::format("{}  {}  tick {}  rtt {} ms  {}  stalled {:.1f} s{}", who, kind,
                         match.shown_world().tick(), s.round_trip_ms, lag, s.stalled_ms / 1000.0,
                         match.state() == MatchState::finished ? "  (match over)" : "");
    }
    case MatchState::desynced:
    case MatchState::failed:
      break;
  }
  return match.error();
}

void MatchView::draw(const app::detail::AnyGame& game, const MatchPeer& match) {
  Session& s = session();
  // The shown world as it is now: the loop's accumulator just under a tick, so the frame is
  // drawn at the last tick's positions (alpha 1), not the ones before it (the shown world keeps
  // none of its own: the session draws what the match stepped).
  const World& shown = match.shown_world();
  shown.save(snapshot_.world);
  snapshot_.loop = {std::nextafter(shown.settings().dt, 0.0), shown.tick()};
  s.restore(snapshot_);
  app::detail::draw_game(s, game, overlay_, status(match));
}

void MatchView::present() {
#ifdef FIXSTEP_NET_WINDOW
  if (window_) window_->window.present(session().renderer().pixels());
#endif
}

void MatchView::write_last_frame(const app::detail::AnyGame& game, const MatchPeer& match,
                                 const std::string& png) {
  draw(game, match);
  write_png(png, settings_.width, settings_.height, session().renderer().pixels());
}

}  // namespace fixstep::net::detail
