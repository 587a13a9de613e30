// fixstep::net: what a peer adapts to the measured round trip (MatchSettings::
// adapt_to_round_trip): a lockstep host's input delay, a rollback peer's window, the timeouts.
#include <algorithm>
#include <cmath>

#include "match_peer_impl.hpp"

namespace fixstep::net {

std::uint16_t MatchPeer::Impl::input_delay_for(std::uint32_t rtt_ms) const {
  // A remote input for tick t is given when its peer plays tick t - delay; it waits for that
  // peer's next packet (up to a send interval and a frame) and crosses the link (half a round
  // trip; the host's relay to a third player another half): it must arrive by tick t.
  const double dt_ms = def.settings.dt * 1000.0;
  const double ms = rtt_ms + static_cast<double>(settings.send_interval_ms) + 1000.0 / 60.0;
  const double ticks = std::ceil(ms / dt_ms) + 1.0;
  return static_cast<std::uint16_t>(std::clamp(ticks, static_cast<double>(settings.input_delay),
                                               static_cast<double>(max_input_delay)));
}

std::uint16_t MatchPeer::Impl::rollback_window() const {
  if (!shown) return 0;
  if (!settings.adapt_to_round_trip) return settings.max_rollback;
  // The remote inputs of the ticks shown ahead arrive a round trip, two send intervals (ours
  // to be acknowledged... theirs to be sent) and a frame after we play them.
  const double dt_ms = def.settings.dt * 1000.0;
  const double ms =
      static_cast<double>(stats.round_trip_ms) + 2.0 * settings.send_interval_ms + 1000.0 / 60.0;
  const double ticks = std::ceil(ms / dt_ms) + 2.0;
  return static_cast<std::uint16_t>(
      std::clamp(ticks, static_cast<double>(settings.max_rollback),
                 static_cast<double>(std::max(max_rollback_window, settings.max_rollback))));
}

double MatchPeer::Impl::peer_timeout_ms() const {
  if (!settings.adapt_to_round_trip) return settings.peer_timeout_ms;
  return std::max(static_cast<double>(settings.peer_timeout_ms),
                  static_cast<double>(timeout_round_trips) * stats.round_trip_ms);
}

double MatchPeer::Impl::handshake_timeout_ms() const {
  if (!settings.adapt_to_round_trip) return settings.handshake_timeout_ms;
  // The connections' (ENet's connect measured them); a joiner's cookie exchange before.
  std::uint32_t rtt = transport->gate_round_trip_ms().value_or(0);
  for (const detail::Remote& r : remotes) rtt = std::max(rtt, transport->round_trip_ms(r.conn));
  return std::max(static_cast<double>(settings.handshake_timeout_ms),
                  static_cast<double>(timeout_round_trips) * rtt);
}

}  // namespace fixstep::net
