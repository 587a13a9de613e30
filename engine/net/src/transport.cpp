// fixstep::net: datagrams over ENet (fixstep/net/net_transport.hpp).
#include <enet/enet.h>
#include <fmt/format.h>

#include <mutex>

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

}  // namespace

struct Transport::Impl {
  ENetHost* host = nullptr;
  std::vector<ENetPeer*> peers;  ///< by id (ENet's incomingPeerID on a listening host)
  TimeoutSettings timeouts;
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

Transport::Transport(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Transport::Transport(Transport&&) noexcept = default;
Transport& Transport::operator=(Transport&&) noexcept = default;
Transport::~Transport() = default;

Transport Transport::listen(const Address& bind, std::size_t max_peers, TimeoutSettings timeouts) {
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
  return Transport(std::move(impl));
}

Transport Transport::connect(const Address& host, TimeoutSettings timeouts, const Address& bind) {
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
  ENetEvent ev{};
  if (enet_host_service(impl_->host, &ev, timeout_ms) <= 0) return out;
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

std::uint32_t Transport::round_trip_ms(std::uint32_t peer) const {
  const ENetPeer* p = impl_->peer(peer);
  return p != nullptr ? p->roundTripTime : 0;
}

TransportCounters Transport::counters() const {
  const ENetHost* h = impl_->host;
  return {h->totalSentPackets, h->totalSentData, h->totalReceivedPackets, h->totalReceivedData};
}

std::uint16_t Transport::port() const {
  return impl_->host->address.port;
}

std::string Transport::peer_address(std::uint32_t peer) const {
  const ENetPeer* p = impl_->peer(peer);
  return p != nullptr ? format_address(p->address) : std::string();
}

}  // namespace fixstep::net
