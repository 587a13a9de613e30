// fixstep::net: the link conditioner's UDP relay (fixstep/net/link_conditioner.hpp).
#include <arpa/inet.h>
#include <fcntl.h>
#include <fmt/format.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <queue>

#include "fixstep/core/world_settings.hpp"
#include "fixstep/net/link_conditioner.hpp"

namespace fixstep::net {

namespace {

double now_ms() {
  return std::chrono::duration<double, std::milli>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

sockaddr_in socket_address(const Address& a) {
  sockaddr_in out{};
  out.sin_family = AF_INET;
  out.sin_port = htons(a.port);
  if (inet_pton(AF_INET, a.host.c_str(), &out.sin_addr) != 1) {
    throw TransportError(fmt::format("link conditioner: `{}` is not an IPv4 address", a.host));
  }
  return out;
}

/// A non-blocking UDP socket bound to `bind`.
int udp_socket(const Address& bind) {
  const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd < 0)
    throw TransportError(fmt::format("link conditioner: socket: {}", std::strerror(errno)));
  const sockaddr_in a = socket_address(bind);
  if (::bind(fd, reinterpret_cast<const sockaddr*>(&a), sizeof a) != 0) {
    const int err = errno;
    ::close(fd);
    throw TransportError(fmt::format("link conditioner: cannot bind {}:{}: {}", bind.host,
                                     bind.port, std::strerror(err)));
  }
  return fd;
}

bool same(const sockaddr_in& a, const sockaddr_in& b) {
  return a.sin_addr.s_addr == b.sin_addr.s_addr && a.sin_port == b.sin_port;
}

}  // namespace

namespace relay {

struct Flow {
  sockaddr_in peer{};  ///< the peer's address, as the relay's listening socket sees it
  int upstream = -1;   ///< the socket its datagrams go on from
  LinkModel to_host, to_peer;
};

struct Pending {
  double at = 0.0;
  std::uint64_t order = 0;  ///< ties in time keep the order of decisions
  int fd = -1;
  sockaddr_in to{};
  std::vector<std::uint8_t> bytes;
  bool operator>(const Pending& o) const { return at != o.at ? at > o.at : order > o.order; }
};

}  // namespace relay

struct LinkConditioner::Impl {
  using Flow = relay::Flow;
  using Pending = relay::Pending;
  LinkSettings settings;
  sockaddr_in upstream{};
  int listen_fd = -1;
  std::vector<std::unique_ptr<Flow>> flows;
  std::priority_queue<Pending, std::vector<Pending>, std::greater<>> queue;
  std::uint64_t order = 0;
  std::vector<std::uint8_t> buffer = std::vector<std::uint8_t>(65536);

  ~Impl() {
    if (listen_fd >= 0) ::close(listen_fd);
    for (auto& f : flows) ::close(f->upstream);
  }

  Flow& flow_of(const sockaddr_in& from) {
    for (auto& f : flows) {
      if (same(f->peer, from)) return *f;
    }
    LinkSettings a = settings, b = settings;
    a.seed = settings.seed * 2 * (flows.size() + 1) + 1;  // each flow and direction its own
    b.seed = a.seed + 1;
    auto f = std::make_unique<Flow>(Flow{from, udp_socket(Address{}), LinkModel(a), LinkModel(b)});
    flows.push_back(std::move(f));
    return *flows.back();
  }

  void schedule(LinkModel& model, int fd, const sockaddr_in& to, std::size_t n, double now) {
    for (double at : model.decide(now)) {
      queue.push(Pending{
          at, order++, fd, to, {buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(n)}});
    }
  }

  /// Reads every datagram waiting on fd; from_peer: the listening socket.
  void drain(int fd, Flow* flow, double now) {
    for (;;) {
      sockaddr_in from{};
      socklen_t len = sizeof from;
      const ssize_t n =
          ::recvfrom(fd, buffer.data(), buffer.size(), 0, reinterpret_cast<sockaddr*>(&from), &len);
      if (n < 0) return;  // EAGAIN (nothing more), or an ICMP error of an earlier send
      if (flow == nullptr) {
        Flow& f = flow_of(from);
        schedule(f.to_host, f.upstream, upstream, static_cast<std::size_t>(n), now);
      } else if (same(from, upstream)) {
        schedule(flow->to_peer, listen_fd, flow->peer, static_cast<std::size_t>(n), now);
      }
    }
  }
};

LinkConditioner::LinkConditioner(const Address& upstream, const LinkSettings& settings,
                                 const Address& bind)
    : impl_(std::make_unique<Impl>()) {
  (void)LinkModel(settings);  // refuses bad settings before any socket is made
  impl_->settings = settings;
  impl_->upstream = socket_address(upstream);
  impl_->listen_fd = udp_socket(bind);
}

LinkConditioner::~LinkConditioner() = default;

void LinkConditioner::pump() {
  const double now = now_ms();
  impl_->drain(impl_->listen_fd, nullptr, now);
  for (std::size_t i = 0; i < impl_->flows.size(); ++i) {
    impl_->drain(impl_->flows[i]->upstream, impl_->flows[i].get(), now);
  }
  while (!impl_->queue.empty() && impl_->queue.top().at <= now) {
    const relay::Pending& p = impl_->queue.top();
    (void)::sendto(p.fd, p.bytes.data(), p.bytes.size(), 0,
                   reinterpret_cast<const sockaddr*>(&p.to), sizeof p.to);
    impl_->queue.pop();
  }
}

std::uint16_t LinkConditioner::port() const {
  sockaddr_in a{};
  socklen_t len = sizeof a;
  ::getsockname(impl_->listen_fd, reinterpret_cast<sockaddr*>(&a), &len);
  return ntohs(a.sin_port);
}

LinkStats LinkConditioner::stats() const {
  LinkStats s;
  for (const auto& f : impl_->flows) {
    for (const LinkModel* m : {&f->to_host, &f->to_peer}) {
      s.received += m->stats().received;
      s.dropped += m->stats().dropped;
      s.burst_dropped += m->stats().burst_dropped;
      s.duplicated += m->stats().duplicated;
      s.held_back += m->stats().held_back;
      s.delivered += m->stats().delivered;
    }
  }
  return s;
}

}  // namespace fixstep::net
