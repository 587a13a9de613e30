// Datagrams between peers over UDP with ENet: a host that peers connect to, or a peer that
// connects to one; two channels (unreliable unsequenced for inputs, reliable for the rest);
// ENet's round-trip estimate and its connection timeout. Bound to 127.0.0.1 unless told
// otherwise. What the bytes mean is the session's (net_packet.hpp).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "fixstep/net/net_gate.hpp"

namespace fixstep::net {

/// An IPv4 address and UDP port; port 0 binds any free port.
struct Address {
  std::string host = "127.0.0.1";
  std::uint16_t port = 0;
};

/// The channels of a connection.
enum class Channel : std::uint8_t {
  unreliable = 0,  ///< unsequenced: may be lost, duplicated (by the network) or reordered
  reliable = 1,    ///< delivered once, in order, unless the connection breaks
};

/// What Transport::poll reports.
struct TransportEvent {
  /// refused: the host's gate refused our token (a connecting transport with a token).
  enum class Kind : std::uint8_t { none, connected, received, disconnected, refused };
  Kind kind = Kind::none;
  std::uint32_t peer = 0;  ///< the connection's id (Transport::send)
  Channel channel = Channel::unreliable;
  std::vector<std::uint8_t> bytes{};  ///< received: the datagram
};

/// Timeouts of a connection, ms: ENet declares it lost when an acknowledgement is missing for
/// longer than `minimum_ms` after `limit` retries, or for `maximum_ms` at any rate.
struct TimeoutSettings {
  std::uint32_t minimum_ms = 5000;
  std::uint32_t maximum_ms = 10000;
};

/// What a host put on and took off the wire, all connections together: UDP datagrams and their
/// payload bytes (ENet's own headers, acknowledgements and pings included; not the 28 bytes
/// of IPv4 and UDP headers each datagram adds).
struct TransportCounters {
  std::uint64_t datagrams_sent = 0, bytes_sent = 0;
  std::uint64_t datagrams_received = 0, bytes_received = 0;
};

/// IPv4 (20 bytes, no options) and UDP (8) headers: what each datagram costs besides its payload.
inline constexpr std::uint64_t ip_udp_header_bytes = 28;

/// Thrown when a socket cannot be created, bound or connected (the message names the
/// address and what failed).
class TransportError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// One ENet host: listening for up to `max_peers` (Transport::listen) or connected to one host
/// (Transport::connect). Single-threaded: poll(), send() and the rest from one thread.
class Transport {
 public:
  /// Listens on `bind` (127.0.0.1 and a port, 0 for any) for up to max_peers connections.
  /// With a token, the gate (net_gate.hpp) stands before ENet: ENet reads datagrams only from
  /// an address that proved the token on a cookie of this host's, or that it has a peer at;
  /// without one, anyone may connect (ENet's own handshake, which answers a connect with more
  /// bytes than it carries, and resends).
  [[nodiscard]] static Transport listen(const Address& bind, std::size_t max_peers,
                                        TimeoutSettings timeouts = {},
                                        std::optional<GateKey> token = std::nullopt);
  /// Connects to `host`, from `bind` (127.0.0.1, any port). The connection's id is 0; a
  /// `connected` event follows once ENet's handshake completes. With a token, first the gate's
  /// cookie exchange (its request resent every 500 ms until ENet's connection is up); a host
  /// that holds another token answers `refused`.
  [[nodiscard]] static Transport connect(const Address& host, TimeoutSettings timeouts = {},
                                         const Address& bind = {},
                                         std::optional<GateKey> token = std::nullopt);
  Transport(Transport&&) noexcept;
  Transport& operator=(Transport&&) noexcept;
  ~Transport();

  /// The next event, waiting at most timeout_ms for one (0: only what has arrived); kind none
  /// when there is none.
  [[nodiscard]] TransportEvent poll(std::uint32_t timeout_ms);
  /// Queues `bytes` to `peer` on `channel` (sent by the next poll() or flush()); a peer that
  /// is not connected is ignored.
  void send(std::uint32_t peer, std::span<const std::uint8_t> bytes, Channel channel);
  /// Sends what is queued now.
  void flush();
  /// Ends the connection to `peer` after what is queued to it (a `disconnected` event
  /// follows; poll() until it does).
  void disconnect(std::uint32_t peer);
  /// Drops the connection to `peer` at once, telling it nothing.
  void drop(std::uint32_t peer);
  /// ENet's mean round-trip time to `peer`, ms (0 for an unknown peer).
  [[nodiscard]] std::uint32_t round_trip_ms(std::uint32_t peer) const;
  /// A joiner with a token: the time from its first cookie request to the host's first cookie,
  /// ms (a round trip, longer when requests were lost); nullopt before a cookie came (and on a
  /// host, or a joiner without a token). Known before ENet connects.
  [[nodiscard]] std::optional<std::uint32_t> gate_round_trip_ms() const;
  /// ENet's counts of this host's datagrams and bytes since it was made (ENet keeps them in 32
  /// bits: they wrap after 2^32), the gate's too: received, every datagram the socket got; sent,
  /// ENet's and the gate's cookies, refusals and requests.
  [[nodiscard]] TransportCounters counters() const;
  /// What the gate answered and dropped (a listening transport with a token; zeros otherwise).
  [[nodiscard]] GateCounters gate_counters() const;
  /// The port this host is bound to.
  [[nodiscard]] std::uint16_t port() const;
  /// The remote address of `peer` as "a.b.c.d:port" ("" for an unknown peer).
  [[nodiscard]] std::string peer_address(std::uint32_t peer) const;

 public:
  struct Impl;  ///< internal (transport.cpp)

 private:
  explicit Transport(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace fixstep::net
