// fixstep::net: the cookie exchange and token proof in front of a host's ENet
// (fixstep/net/net_gate.hpp).
#include <algorithm>
#include <cmath>

#include "byte_io.hpp"
#include "fixstep/net/net_gate.hpp"

namespace fixstep::net {

namespace {

/// The first 8 bytes of every gate datagram: magic, version, kind, two reserved zero bytes.
void write_gate_header(detail::ByteWriter& w, GateKind kind) {
  w.u32(gate_magic);
  w.u8(gate_version);
  w.u8(static_cast<std::uint8_t>(kind));
  w.u16(0);
}

/// The kind of a gate datagram of the right size, version and reserved bytes; nullopt for a
/// datagram that is not the gate's at all (no magic), kind 0 for a malformed one.
std::optional<std::uint8_t> gate_kind(std::span<const std::uint8_t> bytes) {
  detail::ByteReader r(bytes);
  if (r.u32() != gate_magic || !r.ok()) return std::nullopt;
  const std::uint8_t version = r.u8(), kind = r.u8();
  const std::uint16_t reserved = r.u16();
  if (!r.ok() || version != gate_version || reserved != 0) return 0;
  static constexpr std::array<std::size_t, 5> sizes{0, cookie_request_bytes, cookie_bytes,
                                                    echo_bytes, refused_bytes};
  if (kind == 0 || kind >= sizes.size() || bytes.size() != sizes[kind]) return 0;
  return kind;
}

}  // namespace

namespace {

/// SipHash-2-4 under `token` of (domain, nonce, window, mac): the joiner's proof (domain 2) and
/// the host's (domain 3) of the same cookie differ, so neither stands for the other.
std::uint64_t proof_of(const GateKey& token, std::uint8_t domain, std::uint64_t nonce,
                       std::uint32_t window, std::uint64_t mac) {
  std::vector<std::uint8_t> m;
  detail::ByteWriter w(m);
  w.u8(domain);
  w.u64(nonce);
  w.u32(window);
  w.u64(mac);
  return siphash24(token, m);
}

}  // namespace

std::uint64_t token_proof(const GateKey& token, std::uint64_t nonce, std::uint32_t window,
                          std::uint64_t cookie_mac) {
  return proof_of(token, 2, nonce, window, cookie_mac);
}

std::uint64_t host_proof(const GateKey& token, std::uint64_t nonce, std::uint32_t window,
                         std::uint64_t cookie_mac) {
  return proof_of(token, 3, nonce, window, cookie_mac);
}

std::uint64_t HostGate::cookie_mac(std::uint32_t ipv4, std::uint16_t port, std::uint64_t nonce,
                                   std::uint32_t window) const {
  std::vector<std::uint8_t> m;
  detail::ByteWriter w(m);
  w.u8(1);
  w.u32(ipv4);
  w.u16(port);
  w.u64(nonce);
  w.u32(window);
  return siphash24(s_.cookie_key, m);
}

HostGate::Admission* HostGate::admission(std::uint32_t ipv4, std::uint16_t port) {
  for (Admission& a : admitted_) {
    if (a.ipv4 == ipv4 && a.port == port) return &a;
  }
  return nullptr;
}

GateVerdict HostGate::on_datagram(std::uint32_t ipv4, std::uint16_t port,
                                  std::span<const std::uint8_t> bytes, double now_ms,
                                  bool connected, std::vector<std::uint8_t>& reply) {
  std::erase_if(admitted_, [&](const Admission& a) { return now_ms >= a.expires_ms; });
  if (connected) {  // ENet has a peer there: its admission no longer counts as a connection opening
    if (Admission* a = admission(ipv4, port)) a->connected = true;
  }
  const std::optional<std::uint8_t> kind = gate_kind(bytes);
  if (!kind) {
    if (connected || admission(ipv4, port) != nullptr) return GateVerdict::to_enet;
    ++counters_.not_admitted;
    counters_.bytes_in += bytes.size();
    return GateVerdict::drop;
  }
  counters_.bytes_in += bytes.size();
  GateVerdict verdict = GateVerdict::drop;
  if (*kind == static_cast<std::uint8_t>(GateKind::cookie_request)) {
    detail::ByteReader r(bytes.subspan(8));
    const std::uint64_t nonce = r.u64();
    const auto window = static_cast<std::uint32_t>(std::floor(now_ms / s_.window_ms));
    reply.clear();
    detail::ByteWriter w(reply);
    write_gate_header(w, GateKind::cookie);
    w.u64(nonce);
    w.u32(window);
    const std::uint64_t mac = cookie_mac(ipv4, port, nonce, window);
    w.u64(mac);
    w.u64(host_proof(s_.token, nonce, window, mac));  // the joiner authenticates the host
    ++counters_.requests;
    verdict = GateVerdict::reply;
  } else if (*kind == static_cast<std::uint8_t>(GateKind::echo)) {
    verdict = on_echo(ipv4, port, bytes, now_ms, reply);
  } else {
    ++counters_.malformed;  // a cookie or a refusal sent to a host, or a bad header
  }
  if (verdict == GateVerdict::reply) counters_.bytes_out += reply.size();
  return verdict;
}

GateVerdict HostGate::on_echo(std::uint32_t ipv4, std::uint16_t port,
                              std::span<const std::uint8_t> bytes, double now_ms,
                              std::vector<std::uint8_t>& reply) {
  detail::ByteReader r(bytes.subspan(8));
  const std::uint64_t nonce = r.u64();
  const std::uint32_t window = r.u32();
  const std::uint64_t mac = r.u64(), proof = r.u64();
  const auto now_window = static_cast<std::uint32_t>(std::floor(now_ms / s_.window_ms));
  if (window != now_window && window + 1 != now_window) {
    // Forged windows count here too: only the host's clock decides, before the MAC is read.
    ++counters_.expired;
    return GateVerdict::drop;
  }
  if (mac != cookie_mac(ipv4, port, nonce, window)) {
    ++counters_.bad_cookie;
    return GateVerdict::drop;
  }
  if (proof != token_proof(s_.token, nonce, window, mac)) {
    ++counters_.bad_token;
    reply.clear();
    detail::ByteWriter w(reply);
    write_gate_header(w, GateKind::refused);
    w.u64(nonce);
    return GateVerdict::reply;
  }
  Admission* had = admission(ipv4, port);
  if (had != nullptr && window <= had->window) {
    // Admitted with this cookie or a later one: a cookie admits its address once (a joiner
    // still connecting echoes the next window's cookie, which extends its admission).
    ++counters_.replayed;
    return GateVerdict::drop;
  }
  const double expires = (static_cast<double>(window) + 2.0) * s_.window_ms;
  if (had != nullptr) {
    *had = {ipv4, port, nonce, window, expires, had->connected};
  } else if (admitted_.size() >= s_.max_admitted) {
    ++counters_.full;
    return GateVerdict::drop;
  } else if (static_cast<std::size_t>(
                 std::count_if(admitted_.begin(), admitted_.end(), [&](const Admission& a) {
                   return a.ipv4 == ipv4 && !a.connected;
                 })) >= s_.max_admitted_per_host) {
    ++counters_.host_full;
    return GateVerdict::drop;
  } else {
    admitted_.push_back({ipv4, port, nonce, window, expires});
  }
  ++counters_.admitted;
  return GateVerdict::drop;
}

std::vector<std::uint8_t> JoinerGate::request() const {
  std::vector<std::uint8_t> out;
  detail::ByteWriter w(out);
  write_gate_header(w, GateKind::cookie_request);
  w.u64(nonce_);
  w.zeros(cookie_request_bytes - w.size());
  return out;
}

JoinerGate::Answer JoinerGate::on_datagram(std::span<const std::uint8_t> bytes,
                                           std::vector<std::uint8_t>& echo) const {
  const std::optional<std::uint8_t> kind = gate_kind(bytes);
  if (!kind || *kind == 0) return Answer::none;
  detail::ByteReader r(bytes.subspan(8));
  if (r.u64() != nonce_) return Answer::none;  // not an answer to us
  if (*kind == static_cast<std::uint8_t>(GateKind::refused)) return Answer::refused;
  if (*kind != static_cast<std::uint8_t>(GateKind::cookie)) return Answer::none;
  const std::uint32_t window = r.u32();
  const std::uint64_t mac = r.u64();
  // A cookie with our nonce that does not prove our token: a host of another match (or a
  // forger on the path): no echo, no connect.
  if (r.u64() != host_proof(token_, nonce_, window, mac)) return Answer::refused;
  echo = *echo_of_cookie(token_, bytes);
  return Answer::cookie;
}

std::optional<std::vector<std::uint8_t>> echo_of_cookie(const GateKey& token,
                                                        std::span<const std::uint8_t> cookie) {
  if (gate_kind(cookie) != static_cast<std::uint8_t>(GateKind::cookie)) return std::nullopt;
  detail::ByteReader r(cookie.subspan(8));
  const std::uint64_t nonce = r.u64();
  const std::uint32_t window = r.u32();
  const std::uint64_t mac = r.u64();
  std::vector<std::uint8_t> echo;
  detail::ByteWriter w(echo);
  write_gate_header(w, GateKind::echo);
  w.u64(nonce);
  w.u32(window);
  w.u64(mac);
  w.u64(token_proof(token, nonce, window, mac));
  return echo;
}

}  // namespace fixstep::net
