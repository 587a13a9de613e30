// A bad network on one machine, without root or netem: a UDP relay on 127.0.0.1 between
// peers that delays, jitters, drops (at random and in bursts), duplicates and reorders their
// datagrams, seeded, so tests and demos play through the conditions a real link has.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "fixstep/net/net_transport.hpp"

namespace fixstep::net {

/// What the link does to each datagram, per direction. Probabilities in [0, 1]; times in ms.
struct LinkSettings {
  double latency_ms = 0.0;  ///< one way, added to every datagram
  double jitter_ms = 0.0;   ///< plus a uniform delay in [0, jitter_ms)
  double loss = 0.0;        ///< each datagram dropped with this probability
  /// Bursts (Gilbert's two-state model): a burst starts before a datagram with probability
  /// burst_start; every datagram of a burst is dropped; a burst lasts burst_length datagrams on
  /// average (each ends it with probability 1 / burst_length, >= 1).
  double burst_start = 0.0;
  double burst_length = 1.0;
  double duplicate = 0.0;  ///< a second copy delivered, [0, jitter_ms + 1) ms after the first
  /// Reordering: a datagram held back an extra reorder_ms with this probability, so datagrams
  /// sent after it overtake it.
  double reorder = 0.0;
  double reorder_ms = 20.0;
  /// For this long after a direction's first datagram nothing is lost (random or burst): a
  /// connection and its handshake get through, then the loss starts. ENet resends a lost
  /// connect after 500 ms, doubling, so at heavy loss a handshake alone can take many seconds.
  double lossless_ms = 0.0;
  std::uint64_t seed = 1;
};

/// Counts of what the link did.
struct LinkStats {
  std::uint64_t received = 0;  ///< datagrams given to the link
  std::uint64_t dropped = 0;   ///< of them, dropped (random and burst loss)
  std::uint64_t burst_dropped = 0;
  std::uint64_t duplicated = 0;
  std::uint64_t held_back = 0;  ///< reordered (held back reorder_ms)
  std::uint64_t delivered = 0;  ///< copies sent on (duplicates included)
};

/// The link's decisions, with no sockets: each datagram arriving at time t gets zero, one or
/// two delivery times. Deterministic for a seed (its own generator, splitmix64).
class LinkModel {
 public:
  /// Throws std::invalid_argument for a probability outside [0, 1], a negative or non-finite
  /// time, or burst_length < 1.
  explicit LinkModel(const LinkSettings& settings);
  /// Delivery times (ms) of a datagram arriving at `now_ms`: empty when dropped.
  [[nodiscard]] std::vector<double> decide(double now_ms);
  [[nodiscard]] const LinkStats& stats() const { return stats_; }

 private:
  double uniform();  ///< [0, 1)
  LinkSettings s_;
  std::uint64_t state_;
  double first_ms_ = -1.0;  ///< the first datagram's arrival (-1: none yet)
  bool in_burst_ = false;
  LinkStats stats_;
};

/// The relay: peers send to port(); each peer's datagrams go on to `upstream` from a socket of
/// its own, and the answers come back to it, both ways through a LinkModel (seeded from
/// settings.seed, per peer and direction). Single-threaded: call pump() often (every
/// millisecond or so) from the thread that polls the peers.
class LinkConditioner {
 public:
  /// Listens on `bind` (127.0.0.1, any port by default). Throws TransportError when a socket
  /// cannot be made or bound, what LinkModel throws for bad settings.
  LinkConditioner(const Address& upstream, const LinkSettings& settings, const Address& bind = {});
  LinkConditioner(const LinkConditioner&) = delete;
  LinkConditioner& operator=(const LinkConditioner&) = delete;
  ~LinkConditioner();

  /// Receives what has arrived and sends what is due; never blocks.
  void pump();
  /// The port the peers send to.
  [[nodiscard]] std::uint16_t port() const;
  /// Both directions' counts of every peer, summed.
  [[nodiscard]] LinkStats stats() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fixstep::net
