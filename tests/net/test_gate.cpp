// The gate in front of a match host's ENet (fixstep/net/net_gate.hpp) as a state machine, no
// sockets: SipHash-2-4 against the paper's vectors, tokens, and each kind of datagram a host
// may get before a handshake: what it answers (never more bytes than it got) and whom it
// admits to ENet.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numeric>
#include <random>
#include <vector>

#include "../fuzz/gate_check.hpp"
#include "fixstep/net/net_gate.hpp"

namespace fixstep::net_test {
namespace {

using net::GateVerdict;
using net::HostGate;
using net::JoinerGate;

net::GateKey key_0_to_15() {
  net::GateKey k{};
  std::iota(k.begin(), k.end(), std::uint8_t{0});
  return k;
}

// Aumasson and Bernstein, "SipHash: a fast short-input PRF" (2012): Appendix A (key 00..0f,
// message 00..0e: a129ca6149be45e5) and the reference implementation's vectors.h (the same
// key, the empty message: 726fdb47dd0e0e31; the 8-byte message 00..07: 93f5f5799a932462).
TEST(Gate, SipHash24MatchesThePapersVectors) {
  std::vector<std::uint8_t> m(15);
  std::iota(m.begin(), m.end(), std::uint8_t{0});
  EXPECT_EQ(net::siphash24(key_0_to_15(), m), 0xa129ca6149be45e5ull);
  EXPECT_EQ(net::siphash24(key_0_to_15(), {}), 0x726fdb47dd0e0e31ull);
  m.resize(8);
  EXPECT_EQ(net::siphash24(key_0_to_15(), m), 0x93f5f5799a932462ull);
}

TEST(Gate, TokensAre32HexDigits) {
  const net::GateKey k = key_0_to_15();
  EXPECT_EQ(net::format_token(k), "000102030405060708090a0b0c0d0e0f");
  EXPECT_EQ(net::parse_token("000102030405060708090A0B0C0D0E0F"), k);
  EXPECT_FALSE(net::parse_token(""));
  EXPECT_FALSE(net::parse_token("000102030405060708090a0b0c0d0e0"));    // 31
  EXPECT_FALSE(net::parse_token("000102030405060708090a0b0c0d0e0f0"));  // 33
  EXPECT_FALSE(net::parse_token("000102030405060708090a0b0c0d0e0g"));
}

constexpr std::uint32_t ip = 0x0100007f;  // 127.0.0.1 as the socket gives it
constexpr double window_ms = 5000.0;

struct Exchange {
  HostGate host{{.token = key_0_to_15()}};
  std::vector<std::uint8_t> reply;
  /// A joiner at `port` with `token` asks at `t` and echoes; the host's verdict on the echo.
  GateVerdict join(std::uint16_t port, const net::GateKey& token, double t,
                   std::uint64_t nonce = 7) {
    const JoinerGate joiner(token, nonce);
    const auto request = joiner.request();
    EXPECT_EQ(host.on_datagram(ip, port, request, t, false, reply), GateVerdict::reply);
    EXPECT_LT(reply.size(), request.size());
    std::vector<std::uint8_t> echo;
    const bool ours = token == key_0_to_15();  // the host's token: its cookie proves it
    EXPECT_EQ(joiner.on_datagram(reply, echo),
              ours ? JoinerGate::Answer::cookie : JoinerGate::Answer::refused);
    if (!ours) echo = *net::echo_of_cookie(token, reply);
    EXPECT_EQ(echo, *net::echo_of_cookie(token, reply));
    last_echo = echo;
    return host.on_datagram(ip, port, echo, t, false, reply);
  }
  std::vector<std::uint8_t> last_echo;
};

TEST(Gate, OnlyAnAddressThatProvesTheTokenOnItsCookieReachesEnet) {
  Exchange x;
  const std::vector<std::uint8_t> enet_connect(52, 0x11);
  // Before: an ENet datagram from anyone is dropped, unanswered.
  EXPECT_EQ(x.host.on_datagram(ip, 4000, enet_connect, 0.0, false, x.reply), GateVerdict::drop);
  EXPECT_EQ(x.join(4000, key_0_to_15(), 0.0), GateVerdict::drop);  // admitted, no answer
  EXPECT_EQ(x.host.counters().admitted, 1u);
  EXPECT_EQ(x.host.on_datagram(ip, 4000, enet_connect, 1.0, false, x.reply), GateVerdict::to_enet);
  // Another port of the same machine is another address: not admitted.
  EXPECT_EQ(x.host.on_datagram(ip, 4001, enet_connect, 1.0, false, x.reply), GateVerdict::drop);
  // A connected address is ENet's whatever the gate holds.
  EXPECT_EQ(x.host.on_datagram(ip, 4002, enet_connect, 1.0, true, x.reply), GateVerdict::to_enet);
  // The admission ends with its cookie (two windows at most).
  EXPECT_EQ(x.host.on_datagram(ip, 4000, enet_connect, 2 * window_ms, false, x.reply),
            GateVerdict::drop);
  EXPECT_EQ(x.host.counters().not_admitted, 3u);
}

// A holder of the token on one machine is admitted on at most max_admitted_per_host (4) ports at
// once, so it cannot take every ENet peer slot of the host; another machine is admitted, and the
// first one's ports again once their admissions expire.
TEST(Gate, OneMachineIsAdmittedOnAtMostFourPortsAtOnce) {
  Exchange x;
  for (std::uint16_t port = 5000; port < 5006; ++port) (void)x.join(port, key_0_to_15(), 0.0);
  EXPECT_EQ(x.host.counters().admitted, 4u);
  EXPECT_EQ(x.host.counters().host_full, 2u);
  EXPECT_EQ(x.host.admitted_count(), 4u);
  std::vector<std::uint8_t> reply, echo;
  const JoinerGate other(key_0_to_15(), 8);
  const std::uint32_t other_ip = ip + 1;
  ASSERT_EQ(x.host.on_datagram(other_ip, 5000, other.request(), 1.0, false, reply),
            GateVerdict::reply);
  ASSERT_EQ(other.on_datagram(reply, echo), JoinerGate::Answer::cookie);
  (void)x.host.on_datagram(other_ip, 5000, echo, 1.0, false, reply);
  EXPECT_EQ(x.host.counters().admitted, 5u);
  (void)x.join(5006, key_0_to_15(), 2 * window_ms);  // the first four have expired
  EXPECT_EQ(x.host.counters().admitted, 6u);
}

// The joiner authenticates the host: a cookie with its nonce that does not prove its token (a
// host of another match, or a forger on the path) is refused, and no echo is made; one bit
// flipped in the host's proof is enough.
TEST(Gate, AJoinerEchoesOnlyACookieThatProvesItsToken) {
  HostGate host{{.token = key_0_to_15()}};
  std::vector<std::uint8_t> cookie, echo;
  const JoinerGate ours(key_0_to_15(), 9);
  ASSERT_EQ(host.on_datagram(ip, 4000, ours.request(), 0.0, false, cookie), GateVerdict::reply);
  ASSERT_EQ(cookie.size(), net::cookie_bytes);
  EXPECT_EQ(ours.on_datagram(cookie, echo), JoinerGate::Answer::cookie);
  EXPECT_EQ(echo.size(), net::echo_bytes);
  net::GateKey other = key_0_to_15();
  other[15] ^= 0x40;
  echo.clear();
  EXPECT_EQ(JoinerGate(other, 9).on_datagram(cookie, echo), JoinerGate::Answer::refused);
  EXPECT_TRUE(echo.empty());
  std::vector<std::uint8_t> forged = cookie;
  forged.back() ^= 0x01;  // the host's proof's last byte
  EXPECT_EQ(ours.on_datagram(forged, echo), JoinerGate::Answer::refused);
  EXPECT_TRUE(echo.empty());
}

TEST(Gate, AWrongTokenIsRefusedInFewerBytesThanItsEcho) {
  Exchange x;
  net::GateKey other = key_0_to_15();
  other[3] ^= 1;
  EXPECT_EQ(x.join(4000, other, 0.0), GateVerdict::reply);
  EXPECT_EQ(x.reply.size(), net::refused_bytes);
  EXPECT_LT(x.reply.size(), x.last_echo.size());
  std::vector<std::uint8_t> unused;
  EXPECT_EQ(JoinerGate(other, 7).on_datagram(x.reply, unused), JoinerGate::Answer::refused);
  // Another joiner's refusal (another nonce) is not ours.
  EXPECT_EQ(JoinerGate(other, 8).on_datagram(x.reply, unused), JoinerGate::Answer::none);
  EXPECT_EQ(x.host.counters().bad_token, 1u);
  EXPECT_EQ(x.host.counters().admitted, 0u);
}

TEST(Gate, ACookieIsGoodForItsAddressAndTwoWindowsOnceOnly) {
  Exchange x;
  ASSERT_EQ(x.join(4000, key_0_to_15(), 100.0), GateVerdict::drop);
  const auto echo = x.last_echo;
  // Replayed from its address: nothing new. From another address: not its cookie.
  EXPECT_EQ(x.host.on_datagram(ip, 4000, echo, 200.0, false, x.reply), GateVerdict::drop);
  EXPECT_EQ(x.host.counters().replayed, 1u);
  EXPECT_EQ(x.host.on_datagram(ip, 4001, echo, 200.0, false, x.reply), GateVerdict::drop);
  EXPECT_EQ(x.host.on_datagram(ip + 1, 4000, echo, 200.0, false, x.reply), GateVerdict::drop);
  EXPECT_EQ(x.host.counters().bad_cookie, 2u);
  // Two windows on, expired, also from its own address once the admission is gone.
  EXPECT_EQ(x.host.on_datagram(ip, 4000, echo, 2 * window_ms + 1, false, x.reply),
            GateVerdict::drop);
  EXPECT_EQ(x.host.counters().expired, 1u);
  EXPECT_EQ(x.host.counters().admitted, 1u);
  // A forged cookie (one bit of its MAC) is not the host's.
  auto forged = echo;
  forged[20] ^= 1;
  EXPECT_EQ(x.host.on_datagram(ip, 4000, forged, 200.0, false, x.reply), GateVerdict::drop);
  EXPECT_EQ(x.host.counters().bad_cookie, 3u);
}

TEST(Gate, NoDatagramDrawsMoreBytesThanItCarriesAndMalformedOnesNone) {
  HostGate host({.token = key_0_to_15()});
  std::vector<std::uint8_t> reply;
  // Every size up to 64 bytes of a request's start, and each kind: at most a reply to an exact
  // cookie request, never larger.
  const auto request = JoinerGate(key_0_to_15(), 1).request();
  for (std::size_t n = 0; n <= 64; ++n) {
    for (std::uint8_t kind = 0; kind < 6; ++kind) {
      std::vector<std::uint8_t> d(n, 0);
      std::copy_n(request.begin(), std::min(n, request.size()), d.begin());
      if (n > 5) d[5] = kind;
      reply.clear();
      const GateVerdict v = host.on_datagram(ip, 4000, d, 0.0, false, reply);
      if (v == GateVerdict::reply) {
        EXPECT_EQ(n, net::cookie_request_bytes);
        EXPECT_LT(reply.size(), n);
      }
    }
  }
  EXPECT_EQ(host.counters().requests, 1u);
  EXPECT_LE(host.counters().bytes_out, host.counters().bytes_in);
}

TEST(Gate, AdmitsAtMostMaxAdmittedAddresses) {
  HostGate host({.token = key_0_to_15(), .max_admitted = 3});
  std::vector<std::uint8_t> reply, echo;
  for (std::uint16_t port = 1; port <= 5; ++port) {
    const JoinerGate joiner(key_0_to_15(), port);
    ASSERT_EQ(host.on_datagram(ip, port, joiner.request(), 0.0, false, reply), GateVerdict::reply);
    ASSERT_EQ(joiner.on_datagram(reply, echo), JoinerGate::Answer::cookie);
    (void)host.on_datagram(ip, port, echo, 0.0, false, reply);
  }
  EXPECT_EQ(host.admitted_count(), 3u);
  EXPECT_EQ(host.counters().full, 2u);
}

/// fuzz_gate's check (tests/fuzz/gate_check.hpp) on its seed corpus and on 3000 sequences of
/// random records: each aborts on a finding.
TEST(Gate, FuzzCheckHoldsOnTheCorpusAndRandomSequences) {
  int files = 0;
  for (const auto& entry :
       std::filesystem::directory_iterator(FIXSTEP_SOURCE_DIR "/tests/fuzz/gate_corpus")) {
    std::ifstream in(entry.path(), std::ios::binary);
    const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), {});
    fuzz::check_gate_datagrams(bytes);
    ++files;
  }
  EXPECT_GE(files, 7);
  std::mt19937_64 rng(58);
  for (int k = 0; k < 3000; ++k) {
    std::vector<std::uint8_t> bytes(rng() % 200);
    for (auto& b : bytes) b = static_cast<std::uint8_t>(rng());
    fuzz::check_gate_datagrams(bytes);
  }
}

}  // namespace
}  // namespace fixstep::net_test
