// The link conditioner: its seeded decisions measured over many datagrams against the
// settings (loss fraction, burst lengths, latency and jitter bounds, duplicates, reordering),
// and the UDP relay on 127.0.0.1 delaying and dropping real datagrams.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <thread>

#include "fixstep/net/link_conditioner.hpp"

namespace fixstep::net_test {
namespace {

using net::LinkModel;
using net::LinkSettings;

TEST(LinkModel, RandomLossWithinToleranceOfTheSetting) {
  for (double loss : {0.05, 0.25}) {
    LinkModel m(LinkSettings{.loss = loss, .seed = 7});
    constexpr int n = 20000;
    int lost = 0;
    for (int i = 0; i < n; ++i) lost += m.decide(i).empty() ? 1 : 0;
    // Binomial: sigma = sqrt(p (1 - p) / n) <= 0.0031; 5 sigma.
    EXPECT_NEAR(static_cast<double>(lost) / n, loss, 0.016) << loss;
    EXPECT_EQ(m.stats().dropped, static_cast<std::uint64_t>(lost));
  }
}

TEST(LinkModel, NothingIsLostForLosslessMsAfterTheFirstDatagram) {
  // Everything lost, in bursts too, but not in the first 100 ms counted from the first
  // datagram (at 50 ms): those at 50-149 ms get through, from 150 ms on none does.
  LinkModel m(
      LinkSettings{.loss = 1.0, .burst_start = 1.0, .burst_length = 3.0, .lossless_ms = 100.0});
  for (int t = 50; t < 300; ++t) EXPECT_EQ(m.decide(t).empty(), t >= 150) << t;
  EXPECT_EQ(m.stats().dropped, 150u);
  EXPECT_THROW(LinkModel(LinkSettings{.lossless_ms = -1.0}), std::invalid_argument);
}

TEST(LinkModel, BurstsHaveTheirMeanLengthAndStationaryFraction) {
  // Gilbert's model: P(enter) = 0.02, P(leave) = 1/5: lost fraction p / (p + q) = 0.0909,
  // bursts 5 datagrams long on average.
  LinkModel m(LinkSettings{.burst_start = 0.02, .burst_length = 5.0, .seed = 3});
  constexpr int n = 200000;
  int lost = 0, bursts = 0;
  bool in_burst = false;
  for (int i = 0; i < n; ++i) {
    const bool dropped = m.decide(i).empty();
    lost += dropped ? 1 : 0;
    if (dropped && !in_burst) ++bursts;
    in_burst = dropped;
  }
  EXPECT_NEAR(static_cast<double>(lost) / n, 0.02 / 0.22, 0.01);
  EXPECT_NEAR(static_cast<double>(lost) / bursts, 5.0, 0.4);
  EXPECT_EQ(m.stats().burst_dropped, static_cast<std::uint64_t>(lost));
}

TEST(LinkModel, LatencyJitterDuplicatesAndReordering) {
  LinkModel m(LinkSettings{.latency_ms = 40.0,
                           .jitter_ms = 10.0,
                           .duplicate = 0.1,
                           .reorder = 0.1,
                           .reorder_ms = 30.0,
                           .seed = 11});
  constexpr int n = 10000;
  int copies = 0, inversions = 0;
  double last_first = -1.0;
  for (int i = 0; i < n; ++i) {
    const double sent = 2.0 * i;  // a datagram every 2 ms
    const std::vector<double> at = m.decide(sent);
    ASSERT_FALSE(at.empty());
    copies += static_cast<int>(at.size());
    for (double t : at) {
      EXPECT_GE(t - sent, 40.0);
      EXPECT_LT(t - sent, 40.0 + 10.0 + 30.0 + 11.0);
    }
    if (at[0] < last_first) ++inversions;
    last_first = at[0];
  }
  EXPECT_NEAR(static_cast<double>(copies - n) / n, 0.1, 0.02);
  EXPECT_NEAR(static_cast<double>(m.stats().held_back) / n, 0.1, 0.02);
  EXPECT_GT(inversions, n / 50);  // held-back datagrams overtaken by later ones
  // Without jitter and reordering, order is kept and the latency is exact.
  LinkModel plain(LinkSettings{.latency_ms = 25.0, .seed = 11});
  for (int i = 0; i < 100; ++i) EXPECT_EQ(plain.decide(i).at(0), i + 25.0);
}

TEST(LinkModel, SeededAndRefusesBadSettings) {
  const LinkSettings s{.jitter_ms = 5.0, .loss = 0.3, .duplicate = 0.2, .seed = 99};
  LinkModel a(s), b(s),
      c(LinkSettings{.jitter_ms = 5.0, .loss = 0.3, .duplicate = 0.2, .seed = 98});
  bool differs = false;
  for (int i = 0; i < 200; ++i) {
    const auto x = a.decide(i), y = b.decide(i), z = c.decide(i);
    EXPECT_EQ(x, y);
    differs = differs || x != z;
  }
  EXPECT_TRUE(differs);
  EXPECT_THROW(LinkModel(LinkSettings{.loss = 1.5}), std::invalid_argument);
  EXPECT_THROW(LinkModel(LinkSettings{.loss = std::nan("")}), std::invalid_argument);
  EXPECT_THROW(LinkModel(LinkSettings{.latency_ms = -1.0}), std::invalid_argument);
  EXPECT_THROW(LinkModel(LinkSettings{.burst_length = 0.5}), std::invalid_argument);
}

int bound_udp() {
  const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a);
  return fd;
}

std::uint16_t port_of(int fd) {
  sockaddr_in a{};
  socklen_t len = sizeof a;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len);
  return ntohs(a.sin_port);
}

double ms_now() {
  return std::chrono::duration<double, std::milli>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

TEST(LinkConditioner, RelaysRealDatagramsLateAndLossy) {
  const int server = bound_udp(), client = bound_udp();
  net::LinkConditioner link({"127.0.0.1", port_of(server)},
                            LinkSettings{.latency_ms = 30.0, .loss = 0.25, .seed = 5});
  sockaddr_in relay{};
  relay.sin_family = AF_INET;
  relay.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  relay.sin_port = htons(link.port());
  constexpr int n = 200;
  std::vector<double> sent_at(n);
  int received = 0;
  double min_delay = 1e9;
  const double start = ms_now();
  for (int i = 0; i < n || ms_now() - start < 400.0; ++i) {
    if (i < n) {
      sent_at[i] = ms_now();
      ::sendto(client, &i, sizeof i, 0, reinterpret_cast<sockaddr*>(&relay), sizeof relay);
    }
    link.pump();
    int got = 0;
    while (::recv(server, &got, sizeof got, 0) == sizeof got) {
      ASSERT_GE(got, 0);
      ASSERT_LT(got, n);
      min_delay = std::min(min_delay, ms_now() - sent_at[got]);
      ++received;
    }
    std::this_thread::sleep_for(std::chrono::microseconds(500));
  }
  ::close(server);
  ::close(client);
  EXPECT_GE(min_delay, 30.0);
  // 150 expected; binomial sigma 6.1.
  EXPECT_NEAR(received, 150, 30);
  EXPECT_EQ(link.stats().received, static_cast<std::uint64_t>(n));
  EXPECT_EQ(link.stats().delivered, static_cast<std::uint64_t>(received));
}

}  // namespace
}  // namespace fixstep::net_test
