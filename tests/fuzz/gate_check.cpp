// fuzz_gate's check (gate_check.hpp).
#include "gate_check.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fixstep/net/net_gate.hpp>
#include <vector>

namespace fixstep::fuzz {

namespace {

[[noreturn]] void finding(const char* what) {
  std::fprintf(stderr, "fuzz_gate: FINDING: %s\n", what);
  std::abort();
}

constexpr net::GateKey token{1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16};
constexpr net::GateKey cookie_key{7, 7, 7, 7, 7, 7, 7, 7, 1, 1, 1, 1, 1, 1, 1, 1};
constexpr double gate_window_ms = 5000.0;
constexpr std::array<double, 8> steps{0, 1, 10, 100, 1000, 2500, 5000, 12000};

struct Address {
  std::uint32_t ip;
  std::uint16_t port;
};
constexpr std::array<Address, 4> addresses{
    {{0x0100007f, 4000}, {0x0100007f, 4001}, {0x0200007f, 4000}, {0x0200007f, 4001}}};

std::uint64_t u64_at(std::span<const std::uint8_t> d, std::size_t at) {
  std::uint64_t v = 0;
  for (std::size_t i = 0; i < 8; ++i) v |= std::uint64_t{d[at + i]} << (8 * i);
  return v;
}

/// Whether `d` is an echo whose proof is the token's for its own nonce, window and cookie.
bool proves_token(std::span<const std::uint8_t> d) {
  if (d.size() != net::echo_bytes) return false;
  const std::uint64_t nonce = u64_at(d, 8);
  const auto window = static_cast<std::uint32_t>(u64_at(d, 16) & 0xffffffffu);
  return u64_at(d, 28) == net::token_proof(token, nonce, window, u64_at(d, 20));
}

class Run {
 public:
  void datagram(std::size_t who, std::span<const std::uint8_t> d, bool connected,
                bool replay = false) {
    const Address a = addresses[who];
    const std::uint64_t admitted_before = gate_.counters().admitted;
    reply_.clear();
    const net::GateVerdict v = gate_.on_datagram(a.ip, a.port, d, now_, connected, reply_);
    if (v == net::GateVerdict::reply && reply_.size() >= d.size()) {
      finding("a reply not smaller than its datagram");
    }
    if (gate_.counters().bytes_out > gate_.counters().bytes_in) finding("bytes out > bytes in");
    if (gate_.admitted_count() > max_admitted) finding("more addresses admitted than the limit");
    if (gate_.counters().admitted > admitted_before) {
      if (!proves_token(d)) finding("an address admitted without a proof of the token");
      if (replay) finding("a replayed echo admitted again");
      expires_[who] = (std::floor(now_ / gate_window_ms) + 2.0) * gate_window_ms;
      last_admitted_.assign(d.begin(), d.end());
      last_admitted_by_ = who;
    }
    if (v == net::GateVerdict::to_enet && !connected && now_ >= expires_[who]) {
      finding("a datagram to ENet from an address neither connected nor admitted");
    }
  }
  /// A joiner's exchange from `who`: request, cookie, echo (with the token or another).
  void exchange(std::size_t who, bool right_token, bool connected) {
    net::GateKey key = token;
    if (!right_token) key[0] ^= 0xff;
    const net::JoinerGate joiner(key, ++nonce_);
    const auto request = joiner.request();
    datagram(who, request, connected);
    std::vector<std::uint8_t> echo;
    const auto answer = joiner.on_datagram(reply_, echo);
    if (answer !=
        (right_token ? net::JoinerGate::Answer::cookie : net::JoinerGate::Answer::refused)) {
      finding(right_token ? "a cookie request drew no cookie"
                          : "a joiner echoed an unproven cookie");
    }
    if (!right_token) echo = net::echo_of_cookie(key, reply_).value_or(std::vector<std::uint8_t>{});
    const std::uint64_t refused = gate_.counters().bad_token;
    datagram(who, echo, connected);
    if (!right_token && gate_.counters().bad_token != refused + 1) {
      finding("a wrong token not refused");
    }
  }
  void replay(std::size_t who, bool connected) {
    if (last_admitted_.empty()) return;
    const auto echo = last_admitted_;
    datagram(who, echo, connected, true);
  }
  void advance(double ms) { now_ += ms; }

 private:
  static constexpr std::size_t max_admitted = 2;
  net::HostGate gate_{{.token = token, .max_admitted = max_admitted, .cookie_key = cookie_key}};
  double now_ = 1e6;  // a steady clock's value, some windows in
  std::uint64_t nonce_ = 0;
  std::array<double, 4> expires_{};
  std::vector<std::uint8_t> reply_, last_admitted_;
  std::size_t last_admitted_by_ = 0;
};

}  // namespace

void check_gate_datagrams(std::span<const std::uint8_t> bytes) {
  Run run;
  std::size_t at = 0;
  while (at < bytes.size()) {
    const std::uint8_t c = bytes[at++];
    const std::size_t who = (c >> 2) & 3u;
    const bool connected = ((c >> 4) & 1u) != 0;
    run.advance(steps[(c >> 5) & 7u]);
    switch (c & 3u) {
      case 0: {
        const std::size_t n = at < bytes.size() ? bytes[at++] : 0;
        const std::size_t len = std::min(n, bytes.size() - at);
        run.datagram(who, bytes.subspan(at, len), connected);
        at += len;
        break;
      }
      case 1:
        run.exchange(who, true, connected);
        break;
      case 2:
        run.exchange(who, false, connected);
        break;
      default:
        run.replay(who, connected);
        break;
    }
  }
}

}  // namespace fixstep::fuzz
