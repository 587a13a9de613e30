// fixstep::net: datagrams over ENet (fixstep/net/net_transport.hpp).
#include <enet/enet.h>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <mutex>
#include <optional>

#include "fixstep/net/net_gate.hpp"
#include "fixstep/net/net_transport.hpp"

namespace fixstep::net {

namespace {

void enet_once() {
  static std::once_flag once;
  std::call_once(once, [] {
    if (enet_initialize() != 0) throw TransportError("ENet: enet_initialize failed");
    std::atexit(enet_deinitialize);
  });
}

ENetAddress enet_address(const Address& a) {
  ENetAddress out{};
  if (enet_address_set_host_ip(&out, a.host.c_str()) != 0) {
    throw TransportError(fmt::format("ENet: `{}` is not an IPv4 address", a.host));
  }
  out.port = a.port;
  return out;
}

std::string format_address(const ENetAddress& a) {
  char ip[64] = {};
  if (enet_address_get_host_ip(&a, ip, sizeof ip) != 0) return fmt::format("?:{}", a.port);
  return fmt::format("{}:{}", ip, a.port);
}

/// ENet's adaptive range coder on every datagram this host sends (kept only where it is
/// smaller) and receives: both ends of a fixstep connection use it; a datagram a few bytes
/// shorter (docs/NETWORK.md, "Bandwidth").
void compress(ENetHost* host) {
  if (enet_host_compress_with_range_coder(host) != 0) {
    throw TransportError("ENet: cannot set up the range coder");
  }
}

double gate_clock_ms() {
  return std::chrono::duration<double, std::milli>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

/// A datagram sent on the host's socket past ENet (the gate's).
void send_raw(ENetHost* host, const ENetAddress& to, std::span<const std::uint8_t> bytes) {
  ENetBuffer buffer;
  buffer.data = const_cast<std::uint8_t*>(bytes.data());  // ENet's C API: not written
  buffer.dataLength = bytes.size();
  (void)enet_socket_send(host->socket, &to, &buffer, 1);
}

/// A joiner's resend interval of its cookie request while ENet's connection is not up.
constexpr double gate_retry_ms = 500.0;

}  // namespace

struct Transport::Impl {
  ENetHost* host = nullptr;
  std::vector<ENetPeer*> peers;  ///< by id (ENet's incomingPeerID on a listening host)
  TimeoutSettings timeouts;
  std::uint64_t raw_datagrams_sent = 0, raw_bytes_sent = 0;  ///< the gate's, past ENet
  // A listening host with a token: the gate before ENet.
  std::optional<HostGate> gate;
  // A connecting transport with a token: the cookie exchange before ENet's connect.
  std::optional<JoinerGate> joiner;
  ENetAddress remote{};
  double last_request_ms = -1e300;
  double first_request_ms = -1.0;         ///< a joiner's first cookie request
  std::optional<double> gate_round_trip;  ///< from it to the first cookie, ms
  bool connect_due = false, refused = false, refused_reported = false;
  std::vector<std::uint8_t> scratch;

  void send_gate(const ENetAddress& to, std::span<const std::uint8_t> bytes) {
    send_raw(host, to, bytes);
    ++raw_datagrams_sent;
    raw_bytes_sent += bytes.size();
  }
  [[nodiscard]] bool has_peer_at(const ENetAddress& a) const {
    for (std::size_t i = 0; i < host->peerCount; ++i) {
      const ENetPeer& p = host->peers[i];
      if (p.state != ENET_PEER_STATE_DISCONNECTED && p.address.host == a.host &&
          p.address.port == a.port)
        return true;
    }
    return false;
  }
  int intercept();
  std::optional<TransportEvent> joiner_step();
  ~Impl() {
    if (host != nullptr) enet_host_destroy(host);
  }
  ENetPeer* peer(std::uint32_t id) const { return id < peers.size() ? peers[id] : nullptr; }
  std::uint32_t id_of(ENetPeer* p) {
    if (peers.size() == 1 && peers[0] == p) return 0;  // a connecting transport's one peer
    const std::uint32_t id = p->incomingPeerID;
    if (id >= peers.size()) peers.resize(id + 1, nullptr);
    peers[id] = p;
    return id;
  }
};

namespace {

/// The transport whose host is being serviced now (ENet's intercept callback has no user
/// pointer; a transport is used from one thread).
thread_local Transport::Impl* servicing = nullptr;

int ENET_CALLBACK intercept(ENetHost* host, ENetEvent* /*event*/) {
  Transport::Impl* impl = servicing;
  return impl != nullptr && impl->host == host ? impl->intercept() : 0;
}

}  // namespace

int Transport::Impl::intercept() {
  const ENetAddress from = host->receivedAddress;
  const std::span<const std::uint8_t> bytes(host->receivedData, host->receivedDataLength);
  if (gate) {
    switch (gate->on_datagram(from.host, from.port, bytes, gate_clock_ms(), has_peer_at(from),
                              scratch)) {
      case GateVerdict::to_enet:
        return 0;
      case GateVerdict::reply:
        send_gate(from, scratch);
        return 1;
      case GateVerdict::drop:
        return 1;
    }
  }
  if (joiner) {
    if (from.host != remote.host || from.port != remote.port) return 1;  // not the host's
    switch (joiner->on_datagram(bytes, scratch)) {
      case JoinerGate::Answer::cookie:
        if (!gate_round_trip && first_request_ms >= 0.0) {
          gate_round_trip = gate_clock_ms() - first_request_ms;
        }
        if (peers.empty() || peers[0]->state != ENET_PEER_STATE_CONNECTED) {
          send_gate(remote, scratch);
          connect_due = peers.empty();
        }
        return 1;
      case JoinerGate::Answer::refused:
        refused = true;
        return 1;
      case JoinerGate::Answer::none:
        return 0;
    }
  }
  return 0;
}

std::optional<TransportEvent> Transport::Impl::joiner_step() {
  if (refused && !refused_reported) {
    refused_reported = true;
    TransportEvent ev;
    ev.kind = TransportEvent::Kind::refused;
    return ev;
  }
  if (refused) return std::nullopt;
  if (connect_due) {
    connect_due = false;
    ENetPeer* peer = enet_host_connect(host, &remote, 2, 0);
    if (peer != nullptr) {
      enet_peer_timeout(peer, ENET_PEER_TIMEOUT_LIMIT, timeouts.minimum_ms, timeouts.maximum_ms);
      peers = {peer};
      enet_host_flush(host);
    }
  }
  const bool up = !peers.empty() && peers[0]->state == ENET_PEER_STATE_CONNECTED;
  const double now = gate_clock_ms();
  if (!up && now - last_request_ms >= gate_retry_ms) {
    last_request_ms = now;
    if (first_request_ms < 0.0) first_request_ms = now;
    send_gate(remote, joiner->request());
  }
  return std::nullopt;
}

Transport::Transport(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Transport::Transport(Transport&&) noexcept = default;
Transport& Transport::operator=(Transport&&) noexcept = default;
Transport::~Transport() = default;

Transport Transport::listen(const Address& bind, std::size_t max_peers, TimeoutSettings timeouts,
                            std::optional<GateKey> token) {
  enet_once();
  const ENetAddress address = enet_address(bind);
  auto impl = std::make_unique<Impl>();
  impl->timeouts = timeouts;
  impl->host = enet_host_create(&address, max_peers, 2, 0, 0);
  if (impl->host == nullptr) {
    throw TransportError(
        fmt::format("ENet: cannot listen on {}:{} (in use, or not an address "
                    "of this machine)",
                    bind.host, bind.port));
  }
  compress(impl->host);
  if (token) {
    // A party behind one address (a NAT, or one machine) may join all at once: the gate's bound
    // on one address's connections still opening is the host's peer slots, not fewer.
    impl->gate.emplace(HostGateSettings{
        .token = *token,
        .max_admitted_per_host = std::max(HostGateSettings{}.max_admitted_per_host, max_peers)});
    impl->host->intercept = intercept;
  }
  return Transport(std::move(impl));
}

Transport Transport::connect(const Address& host, TimeoutSettings timeouts, const Address& bind,
                             std::optional<GateKey> token) {
  enet_once();
  const ENetAddress local = enet_address(bind);
  const ENetAddress remote = enet_address(host);
  auto impl = std::make_unique<Impl>();
  impl->timeouts = timeouts;
  impl->host = enet_host_create(&local, 1, 2, 0, 0);
  if (impl->host == nullptr) {
    throw TransportError(
        fmt::format("ENet: cannot connect from {}:{} (in use, or not an address of this machine)",
                    bind.host, bind.port));
  }
  compress(impl->host);
  if (token) {
    // ENet connects once the host's gate has answered with a cookie (joiner_step).
    const GateKey nonce = random_gate_key();
    std::uint64_t n = 0;
    for (std::size_t i = 0; i < 8; ++i) n |= std::uint64_t{nonce[i]} << (8 * i);
    impl->joiner.emplace(*token, n);
    impl->remote = remote;
    impl->host->intercept = intercept;
    return Transport(std::move(impl));
  }
  ENetPeer* peer = enet_host_connect(impl->host, &remote, 2, 0);
  if (peer == nullptr) {
    throw TransportError(fmt::format("ENet: cannot connect to {}:{}", host.host, host.port));
  }
  enet_peer_timeout(peer, ENET_PEER_TIMEOUT_LIMIT, timeouts.minimum_ms, timeouts.maximum_ms);
  impl->peers = {peer};
  return Transport(std::move(impl));
}

TransportEvent Transport::poll(std::uint32_t timeout_ms) {
  TransportEvent out;
  if (impl_->joiner) {
    if (auto ev = impl_->joiner_step()) return *ev;
  }
  ENetEvent ev{};
  servicing = impl_.get();
  const int got = enet_host_service(impl_->host, &ev, timeout_ms);
  servicing = nullptr;
  if (impl_->joiner && got <= 0) {
    if (auto gate_ev = impl_->joiner_step()) return *gate_ev;
  }
  if (got <= 0) return out;
  out.peer = impl_->id_of(ev.peer);
  switch (ev.type) {
    case ENET_EVENT_TYPE_CONNECT:
      enet_peer_timeout(ev.peer, ENET_PEER_TIMEOUT_LIMIT, impl_->timeouts.minimum_ms,
                        impl_->timeouts.maximum_ms);
      out.kind = TransportEvent::Kind::connected;
      break;
    case ENET_EVENT_TYPE_RECEIVE:
      out.kind = TransportEvent::Kind::received;
      out.channel = ev.channelID == 1 ? Channel::reliable : Channel::unreliable;
      out.bytes.assign(ev.packet->data, ev.packet->data + ev.packet->dataLength);
      enet_packet_destroy(ev.packet);
      break;
    case ENET_EVENT_TYPE_DISCONNECT:
      out.kind = TransportEvent::Kind::disconnected;
      break;
    default:
      break;
  }
  return out;
}

void Transport::send(std::uint32_t peer, std::span<const std::uint8_t> bytes, Channel channel) {
  ENetPeer* p = impl_->peer(peer);
  if (p == nullptr || p->state != ENET_PEER_STATE_CONNECTED) return;
  const bool reliable = channel == Channel::reliable;
  ENetPacket* packet =
      enet_packet_create(bytes.data(), bytes.size(),
                         reliable ? ENET_PACKET_FLAG_RELIABLE : ENET_PACKET_FLAG_UNSEQUENCED);
  if (packet == nullptr) return;
  if (enet_peer_send(p, reliable ? 1 : 0, packet) != 0) enet_packet_destroy(packet);
}

void Transport::flush() {
  enet_host_flush(impl_->host);
}

void Transport::disconnect(std::uint32_t peer) {
  if (ENetPeer* p = impl_->peer(peer)) enet_peer_disconnect_later(p, 0);
}

void Transport::drop(std::uint32_t peer) {
  if (ENetPeer* p = impl_->peer(peer)) enet_peer_reset(p);
}

std::optional<std::uint32_t> Transport::gate_round_trip_ms() const {
  if (!impl_->gate_round_trip) return std::nullopt;
  return static_cast<std::uint32_t>(std::min(*impl_->gate_round_trip, 4.0e9));
}

std::uint32_t Transport::round_trip_ms(std::uint32_t peer) const {
  const ENetPeer* p = impl_->peer(peer);
  return p != nullptr ? p->roundTripTime : 0;
}

TransportCounters Transport::counters() const {
  const ENetHost* h = impl_->host;
  return {h->totalSentPackets + impl_->raw_datagrams_sent, h->totalSentData + impl_->raw_bytes_sent,
          h->totalReceivedPackets, h->totalReceivedData};
}

GateCounters Transport::gate_counters() const {
  return impl_->gate ? impl_->gate->counters() : GateCounters{};
}

std::uint16_t Transport::port() const {
  return impl_->host->address.port;
}

std::string Transport::peer_address(std::uint32_t peer) const {
  const ENetPeer* p = impl_->peer(peer);
  return p != nullptr ? format_address(p->address) : std::string();
}

}  // namespace fixstep::net
