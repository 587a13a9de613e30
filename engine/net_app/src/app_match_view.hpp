// Internal to fixstep::net_app: what a peer of a match shows, its window and its frames: the
// match's shown world drawn through a Session (restored from the shown world each frame) with
// the game's drawing and a line of the match's state.
#pragma once

#include <fixstep/app/game_level.hpp>
#include <fixstep/app/game_model.hpp>
#include <fixstep/app/session.hpp>
#include <fixstep/core/input.hpp>
#include <fixstep/net/match_peer.hpp>
#include <memory>
#include <optional>
#include <string>

namespace fixstep::net::detail {

class MatchView {
 public:
  /// Nothing is made yet: the session (and its renderer) when the first frame is drawn, the
  /// window by open_window(). `kind` names the session asked for while the match connects
  /// ("lockstep", "rollback", "the host's session"); once it plays, the HUD names the kind played.
  MatchView(const app::detail::Level& level, const app::Settings& settings, std::string kind);
  MatchView(const MatchView&) = delete;
  MatchView& operator=(const MatchView&) = delete;
  ~MatchView();

  /// Opens the window. Throws WindowError when there is no display, std::runtime_error when
  /// the build has no window.
  void open_window(const std::string& title);
  /// The window's events of this frame: the pointer and buttons into `sampler`, then the
  /// game's input() (unless `bot`: the autopilot plays). Returns false on Esc or close.
  bool poll_window(InputSampler& sampler, app::detail::AnyGame& game, const World& shown, bool bot);
  /// Draws the match's shown world, the game's drawing (`game`: the rules' state, seated as
  /// the local player) and the match's line.
  void draw(const app::detail::AnyGame& game, const MatchPeer& match);
  /// Shows the last frame drawn in the window.
  void present();
  /// Draws the frame and writes it as a PNG (throws what write_png throws).
  void write_last_frame(const app::detail::AnyGame& game, const MatchPeer& match,
                        const std::string& png);

 private:
  Session& session();
  [[nodiscard]] std::string status(const MatchPeer& match) const;

  const app::detail::Level& level_;
  const app::Settings& settings_;
  std::string kind_;
  std::optional<Session> session_;
  Session::Snapshot snapshot_;
  app::Overlay overlay_;
  struct WindowHolder;
  std::unique_ptr<WindowHolder> window_;
};

}  // namespace fixstep::net::detail
