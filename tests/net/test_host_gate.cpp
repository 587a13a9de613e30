// A match host's gate on real sockets (127.0.0.1): raw UDP sockets play the attacker, sending
// ENet connects and gate datagrams, and count every byte the host sends back; MatchPeer
// joiners without the token, or with another, are refused with a message. BAD_INPUTS rows
// N16–N19.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <stdexcept>
#include <vector>

#include "net_match.hpp"

namespace fixstep::net_test {
namespace {

using net::MatchPeer;
using net::MatchState;

/// A non-blocking UDP socket on 127.0.0.1 (any port), closed with it.
class RawSocket {
 public:
  RawSocket() : fd_(::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK, 0)) {
    if (fd_ < 0) throw std::runtime_error("socket");
    sockaddr_in a = loopback(0);
    if (::bind(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0)
      throw std::runtime_error("bind");
  }
  RawSocket(const RawSocket&) = delete;
  RawSocket& operator=(const RawSocket&) = delete;
  ~RawSocket() { ::close(fd_); }
  [[nodiscard]] std::uint16_t port() const {
    sockaddr_in a{};
    socklen_t n = sizeof a;
    ::getsockname(fd_, reinterpret_cast<sockaddr*>(&a), &n);
    return ntohs(a.sin_port);
  }
  void send_to(std::uint16_t port, const std::vector<std::uint8_t>& bytes) {
    sockaddr_in a = loopback(port);
    const auto sent =
        ::sendto(fd_, bytes.data(), bytes.size(), 0, reinterpret_cast<sockaddr*>(&a), sizeof a);
    ASSERT_EQ(sent, static_cast<ssize_t>(bytes.size()));
    bytes_sent += bytes.size();
  }
  /// Every datagram waiting, counted; the last one kept.
  void drain() {
    std::vector<std::uint8_t> buffer(2048);
    for (;;) {
      const auto n = ::recv(fd_, buffer.data(), buffer.size(), 0);
      if (n < 0) return;
      ++datagrams_received;
      bytes_received += static_cast<std::size_t>(n);
      last.assign(buffer.begin(), buffer.begin() + n);
    }
  }
  std::size_t bytes_sent = 0, bytes_received = 0, datagrams_received = 0;
  std::vector<std::uint8_t> last;

 private:
  static sockaddr_in loopback(std::uint16_t port) {
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(port);
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    return a;
  }
  int fd_;
};

/// The datagram ENet sends to connect (its connect command, as a joiner's first datagram was
/// before the gate): caught on a raw socket.
std::vector<std::uint8_t> enet_connect_datagram() {
  RawSocket catcher;
  net::Transport client = net::Transport::connect({"127.0.0.1", catcher.port()});
  for (int k = 0; k < 500 && catcher.datagrams_received == 0; ++k) {
    (void)client.poll(1);
    catcher.drain();
  }
  return catcher.last;
}

/// Polls `host` (and `others`) for `ms`, draining every socket of `flood`.
void serve(MatchPeer& host, std::vector<std::unique_ptr<RawSocket>>& flood, int ms,
           const std::vector<MatchPeer*>& others = {}) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(ms);
  while (std::chrono::steady_clock::now() < end) {
    host.poll(1);
    for (MatchPeer* p : others) p->poll(0);
    for (auto& s : flood) s->drain();
  }
}

/// Polls `host` until `raw` has received `count` datagrams (at most 2 s).
void await_datagrams(MatchPeer& host, std::vector<std::unique_ptr<RawSocket>>& socks,
                     const RawSocket& raw, std::size_t count) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(2);
  while (raw.datagrams_received < count && std::chrono::steady_clock::now() < end) {
    serve(host, socks, 1);
  }
}

/// Before the gate, 15 connects (one each from 15 ports) filled ENet's 15 peer slots for half
/// a minute and each drew its verify command, resent: 3 times its bytes and more. Now: no byte
/// back, and a joiner with the token joins at once.
TEST(HostGate, AFloodOfEnetConnectsDrawsNothingAndBlocksNoJoiner) {
  const std::vector<std::uint8_t> connect = enet_connect_datagram();
  ASSERT_GE(connect.size(), 20u);  // range-coded, as a fixstep joiner sends it
  const net::MatchSettings s = match(2, 0);
  MatchPeer host = MatchPeer::host(billiards().def, s, {"127.0.0.1", 0});
  std::vector<std::unique_ptr<RawSocket>> flood;
  std::size_t in = 0, out = 0;
  for (int k = 0; k < 32; ++k) {  // twice the peer slots, each sent twice
    flood.push_back(std::make_unique<RawSocket>());
    flood.back()->send_to(host.port(), connect);
    flood.back()->send_to(host.port(), connect);
  }
  serve(host, flood, 1200);  // past ENet's first resend of a verify (500 ms)
  for (const auto& f : flood) {
    in += f->bytes_sent;
    out += f->bytes_received;
  }
  EXPECT_EQ(out, 0u) << "the host answered " << out << " bytes to " << in;
  EXPECT_EQ(host.gate_counters().not_admitted, 64u);
  MatchPeer joiner = MatchPeer::join(billiards().def, s, {"127.0.0.1", host.port()});
  const auto start = std::chrono::steady_clock::now();
  while (joiner.state() == MatchState::connecting &&
         std::chrono::steady_clock::now() - start < std::chrono::seconds(3)) {
    serve(host, flood, 1, {&joiner});
  }
  EXPECT_EQ(joiner.state(), MatchState::playing) << joiner.error();
  EXPECT_EQ(joiner.slot(), 1);
}

/// Cookie requests, echoes with a wrong token and garbage from one raw socket: the host
/// answers in fewer bytes than it got, each unauthenticated exchange and all of them.
TEST(HostGate, NoUnauthenticatedExchangeDrawsMoreBytesThanItSent) {
  const net::MatchSettings s = match(2, 0);
  MatchPeer host = MatchPeer::host(billiards().def, s, {"127.0.0.1", 0});
  std::vector<std::unique_ptr<RawSocket>> socks;
  socks.push_back(std::make_unique<RawSocket>());
  RawSocket& raw = *socks.back();
  net::GateKey wrong = *net::parse_token(s.token);
  wrong[0] ^= 0x80;
  for (std::uint64_t nonce = 1; nonce <= 20; ++nonce) {
    const net::JoinerGate joiner(wrong, nonce);
    const std::size_t before_in = raw.bytes_sent, before_out = raw.bytes_received;
    raw.send_to(host.port(), joiner.request());
    await_datagrams(host, socks, raw, 2 * nonce - 1);
    ASSERT_EQ(raw.last.size(), net::cookie_bytes);
    std::vector<std::uint8_t> echo;
    // The host's cookie does not prove this token: a joiner refuses it; echo it regardless.
    ASSERT_EQ(joiner.on_datagram(raw.last, echo), net::JoinerGate::Answer::refused);
    echo = *net::echo_of_cookie(wrong, raw.last);
    raw.send_to(host.port(), echo);
    raw.send_to(host.port(), std::vector<std::uint8_t>(60, 0xab));  // garbage
    await_datagrams(host, socks, raw, 2 * nonce);
    EXPECT_EQ(raw.last.size(), net::refused_bytes);
    EXPECT_LT(raw.bytes_received - before_out, raw.bytes_sent - before_in);
  }
  serve(host, socks, 100);  // anything late (the garbage draws nothing)
  EXPECT_EQ(host.gate_counters().bad_token, 20u);
  EXPECT_EQ(host.gate_counters().admitted, 0u);
  EXPECT_EQ(raw.datagrams_received, 40u);  // a cookie and a refusal each, nothing for garbage
  const double ratio =
      static_cast<double>(raw.bytes_received) / static_cast<double>(raw.bytes_sent);
  EXPECT_LT(ratio, 0.4) << raw.bytes_received << " bytes out for " << raw.bytes_sent << " in";
  EXPECT_EQ(host.state(), MatchState::playing);
}

TEST(HostGate, AJoinerWithoutTheTokenOrWithAnotherIsRefusedWithAMessage) {
  const net::MatchSettings s = match(2, 0);
  MatchPeer host = MatchPeer::host(billiards().def, s, {"127.0.0.1", 0});
  net::MatchSettings none = s;
  none.token.clear();
  try {
    (void)MatchPeer::join(billiards().def, none, {"127.0.0.1", host.port()});
    ADD_FAILURE() << "joined without a token";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("joining needs the host's token"), std::string::npos)
        << e.what();
  }
  net::MatchSettings other = s;
  other.token = "ffffffffffffffffffffffffffffffff";
  MatchPeer stranger = MatchPeer::join(billiards().def, other, {"127.0.0.1", host.port()});
  const auto start = std::chrono::steady_clock::now();
  while (stranger.state() == MatchState::connecting &&
         std::chrono::steady_clock::now() - start < std::chrono::seconds(3)) {
    host.poll(1);
    stranger.poll(0);
  }
  EXPECT_EQ(stranger.state(), MatchState::failed);
  EXPECT_NE(stranger.error().find("refused our token"), std::string::npos) << stranger.error();
  // A host's random token, when none is given: 32 hex digits, another each time.
  net::MatchSettings open = s;
  open.token.clear();
  const MatchPeer a = MatchPeer::host(billiards().def, open, {"127.0.0.1", 0});
  const MatchPeer b = MatchPeer::host(billiards().def, open, {"127.0.0.1", 0});
  EXPECT_TRUE(net::parse_token(a.token()));
  EXPECT_NE(a.token(), b.token());
}

}  // namespace
}  // namespace fixstep::net_test
