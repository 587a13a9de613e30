// fixstep::net's transport on loopback: connect, datagrams on both channels intact, ENet's
// round-trip estimate, a connection timeout when the other side goes silent. Every wait is
// bounded.
#include <gtest/gtest.h>

#include <chrono>
#include <optional>

#include "fixstep/net/net_transport.hpp"

namespace fixstep::net_test {
namespace {

using net::Transport;
using net::TransportEvent;
using Kind = TransportEvent::Kind;

/// Polls `a` and `b` (b may be null) until `a` reports an event of `kind`, at most `ms`.
std::optional<TransportEvent> wait_for(Transport& a, Transport* b, Kind kind, int ms) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(ms);
  while (std::chrono::steady_clock::now() < end) {
    if (b != nullptr) {
      while (b->poll(0).kind != Kind::none) {
      }
    }
    TransportEvent ev = a.poll(1);
    if (ev.kind == kind) return ev;
  }
  return std::nullopt;
}

TEST(NetTransport, ConnectsAndCarriesBothChannels) {
  Transport host = Transport::listen({"127.0.0.1", 0}, 4);
  ASSERT_NE(host.port(), 0);
  Transport client = Transport::connect({"127.0.0.1", host.port()});
  ASSERT_TRUE(wait_for(client, &host, Kind::connected, 3000));
  const std::vector<std::uint8_t> a{1, 2, 3}, b{9, 8};
  client.send(0, a, net::Channel::reliable);
  client.send(0, b, net::Channel::unreliable);
  client.flush();
  std::optional<TransportEvent> first, second;
  // The host saw the connection first (wait_for polled it), then the two datagrams.
  first = wait_for(host, &client, Kind::received, 3000);
  second = wait_for(host, &client, Kind::received, 3000);
  ASSERT_TRUE(first && second);
  const TransportEvent& rel = first->channel == net::Channel::reliable ? *first : *second;
  const TransportEvent& unrel = first->channel == net::Channel::reliable ? *second : *first;
  EXPECT_EQ(rel.bytes, a);
  EXPECT_EQ(unrel.bytes, b);
  EXPECT_EQ(unrel.channel, net::Channel::unreliable);
  EXPECT_NE(host.peer_address(rel.peer).find("127.0.0.1:"), std::string::npos);
}

TEST(NetTransport, RoundTripEstimateFallsToLoopback) {
  Transport host = Transport::listen({"127.0.0.1", 0}, 1);
  Transport client = Transport::connect({"127.0.0.1", host.port()});
  ASSERT_TRUE(wait_for(client, &host, Kind::connected, 3000));
  // Reliable datagrams both ways: each acknowledgement updates the estimate (ENet starts at
  // 500 ms and moves 1/8 of the way to each measurement).
  const std::vector<std::uint8_t> ping{1};
  for (int i = 0; i < 60; ++i) {
    client.send(0, ping, net::Channel::reliable);
    client.flush();
    ASSERT_TRUE(wait_for(host, &client, Kind::received, 2000));
    host.flush();
    (void)client.poll(2);
  }
  EXPECT_LT(client.round_trip_ms(0), 50u);
  EXPECT_EQ(client.round_trip_ms(7), 0u);  // no such peer
}

TEST(NetTransport, SilentPeerTimesOut) {
  std::optional<Transport> host = Transport::listen({"127.0.0.1", 0}, 1);
  Transport client = Transport::connect({"127.0.0.1", host->port()}, {200, 400});
  ASSERT_TRUE(wait_for(client, &*host, Kind::connected, 3000));
  host.reset();  // gone without a word
  const auto start = std::chrono::steady_clock::now();
  const std::vector<std::uint8_t> ping{1};
  client.send(0, ping, net::Channel::reliable);  // something waiting for an acknowledgement
  ASSERT_TRUE(wait_for(client, nullptr, Kind::disconnected, 5000));
  const double waited =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  EXPECT_GE(waited, 150.0);
}

TEST(NetTransport, BadAddressesAreClearErrors) {
  EXPECT_THROW((void)Transport::listen({"not-an-ip", 0}, 1), net::TransportError);
  Transport a = Transport::listen({"127.0.0.1", 0}, 1);
  try {
    (void)Transport::listen({"127.0.0.1", a.port()}, 1);
    FAIL() << "a port in use was bound twice";
  } catch (const net::TransportError& e) {
    EXPECT_NE(std::string(e.what()).find(std::to_string(a.port())), std::string::npos);
  }
}

}  // namespace
}  // namespace fixstep::net_test
