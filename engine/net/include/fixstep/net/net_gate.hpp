// The gate in front of a match host's ENet: a stateless cookie exchange on the host's UDP
// socket, and the proof of the match's token, before ENet sees a single datagram of a peer.
//
//   joiner                                   host
//   cookie request (40 bytes, a nonce)  ->
//                                       <-   cookie (28 bytes: the nonce, a time window and
//                                            SipHash(host key, address, port, nonce, window))
//   echo (36 bytes: the cookie and a     ->  checks the cookie (this address, this window or
//   proof, SipHash(token, the cookie))       the one before), then the proof; admits the
//                                            address to ENet until the cookie expires, or
//                                       <-   refused (16 bytes) when the proof is wrong
//   ENet's own connect                   ->  (only from an admitted or connected address)
//
// Every reply is smaller than the datagram it answers, and the host keeps no state for a peer
// until it has proven the token from an address that receives the host's datagrams (the
// cookie). Why this scheme, and what an attacker can and cannot do: docs/NETWORK.md,
// "Connecting".
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace fixstep::net {

/// A 128-bit key: the host's cookie key (random per host) or the match's token.
using GateKey = std::array<std::uint8_t, 16>;

/// SipHash-2-4 of `bytes` under `key`: a keyed 64-bit pseudo-random function, designed as a MAC
/// of short messages (J.-P. Aumasson and D. J. Bernstein, "SipHash: a fast short-input PRF",
/// INDOCRYPT 2012; 2 compression rounds, 4 finalization rounds, the key and message bytes
/// read little-endian). Forging a tag without the key takes about 2^64 guesses.
[[nodiscard]] std::uint64_t siphash24(const GateKey& key, std::span<const std::uint8_t> bytes);

/// 16 bytes from std::random_device.
[[nodiscard]] GateKey random_gate_key();
/// A token as 32 lowercase hexadecimal digits.
[[nodiscard]] std::string format_token(const GateKey& token);
/// A token from exactly 32 hexadecimal digits (either case); nullopt otherwise.
[[nodiscard]] std::optional<GateKey> parse_token(std::string_view text);

/// First four bytes of every gate datagram ("FXSK" little-endian). As an ENet header they
/// name peer 0x658 with the sent-time flag: no ENet host of fewer peers takes them.
inline constexpr std::uint32_t gate_magic = 0x4b535846u;
inline constexpr std::uint8_t gate_version = 2;
enum class GateKind : std::uint8_t { cookie_request = 1, cookie = 2, echo = 3, refused = 4 };
/// Sizes, bytes: each reply is smaller than what it answers (no amplification).
inline constexpr std::size_t cookie_request_bytes = 40;
inline constexpr std::size_t cookie_bytes = 36;
inline constexpr std::size_t echo_bytes = 36;
inline constexpr std::size_t refused_bytes = 16;
static_assert(cookie_bytes < cookie_request_bytes && refused_bytes < echo_bytes);

/// What a host's gate counted: datagrams it answered or dropped itself (ENet never saw them),
/// and their bytes (UDP payload).
struct GateCounters {
  std::uint64_t requests = 0;      ///< cookie requests answered with a cookie
  std::uint64_t admitted = 0;      ///< echoes with a valid cookie and proof: address admitted
  std::uint64_t bad_cookie = 0;    ///< echoes whose cookie is not this address's, or forged
  std::uint64_t expired = 0;       ///< echoes of a cookie older than two windows
  std::uint64_t bad_token = 0;     ///< echoes with a valid cookie and a wrong proof (refused)
  std::uint64_t replayed = 0;      ///< echoes of a cookie this address was admitted with, or
                                   ///< of one older than that
  std::uint64_t full = 0;          ///< valid echoes dropped: max_admitted addresses admitted
  std::uint64_t host_full = 0;     ///< valid echoes dropped: max_admitted_per_host ports of
                                   ///< that IPv4 address admitted
  std::uint64_t malformed = 0;     ///< gate datagrams of a wrong size, version or kind
  std::uint64_t not_admitted = 0;  ///< other datagrams from an address neither admitted nor
                                   ///< connected: dropped before ENet reads them
  std::uint64_t bytes_in = 0, bytes_out = 0;  ///< of the datagrams above, and the replies
};

/// What the host does with a datagram.
enum class GateVerdict : std::uint8_t {
  to_enet,  ///< from a connected or admitted address: ENet's
  reply,    ///< answer it with `reply` (a cookie or a refusal), nothing else
  drop,     ///< nothing
};

struct HostGateSettings {
  GateKey token{};                 ///< the match's token (the joiners' proof)
  std::uint32_t window_ms = 5000;  ///< a cookie is good for 1 to 2 windows
  std::size_t max_admitted = 64;   ///< addresses admitted at once (each by a proof)
  /// Ports of one IPv4 address admitted at once and not yet connected (an admitted address
  /// counts until ENet has a peer there, or its cookie expires): a holder of the token on one
  /// machine opens at most this many ENet connections at a time (each holds a peer slot until it
  /// completes the match's handshake or handshake_timeout_ms passes). A match's transport sets it
  /// to its peer slots (at least 4), so that players behind one address (a NAT, a LAN party on
  /// one machine) can all join at once.
  std::size_t max_admitted_per_host = 4;
  GateKey cookie_key = random_gate_key();  ///< the host's own, never sent
};

/// The host's side: a state machine of datagrams. Its only state is the admitted addresses
/// (at most max_admitted, each until its cookie expires), and only a proof of the token adds
/// one. Single-threaded.
class HostGate {
 public:
  explicit HostGate(HostGateSettings settings) : s_(settings) {}
  /// A datagram from ipv4:port (as the socket gave them: any fixed byte order) at now_ms (a
  /// steady clock); `connected`: ENet has a peer at that address. Fills `reply` for
  /// GateVerdict::reply.
  [[nodiscard]] GateVerdict on_datagram(std::uint32_t ipv4, std::uint16_t port,
                                        std::span<const std::uint8_t> bytes, double now_ms,
                                        bool connected, std::vector<std::uint8_t>& reply);
  [[nodiscard]] const GateCounters& counters() const { return counters_; }
  [[nodiscard]] std::size_t admitted_count() const { return admitted_.size(); }

 private:
  struct Admission {
    std::uint32_t ipv4 = 0;
    std::uint16_t port = 0;
    std::uint64_t nonce = 0;
    std::uint32_t window = 0;
    double expires_ms = 0.0;
    bool connected = false;  ///< ENet has a peer there (not counted by max_admitted_per_host)
  };
  [[nodiscard]] std::uint64_t cookie_mac(std::uint32_t ipv4, std::uint16_t port,
                                         std::uint64_t nonce, std::uint32_t window) const;
  GateVerdict on_echo(std::uint32_t ipv4, std::uint16_t port, std::span<const std::uint8_t> bytes,
                      double now_ms, std::vector<std::uint8_t>& reply);
  [[nodiscard]] Admission* admission(std::uint32_t ipv4, std::uint16_t port);
  HostGateSettings s_;
  GateCounters counters_;
  std::vector<Admission> admitted_;
};

/// The joiner's side: the request it sends (again, while ENet's connection is not up), and what
/// it makes of the host's answers.
class JoinerGate {
 public:
  JoinerGate(const GateKey& token, std::uint64_t nonce) : token_(token), nonce_(nonce) {}
  [[nodiscard]] std::vector<std::uint8_t> request() const;
  enum class Answer : std::uint8_t { none, cookie, refused };
  /// A datagram from the host: `cookie` fills `echo` (send it, then connect); `refused` the
  /// host holds another token: it refused ours, or its cookie does not prove ours (host_proof;
  /// the joiner authenticates the host so); `none` not a gate answer of ours (ENet's, or
  /// stale).
  [[nodiscard]] Answer on_datagram(std::span<const std::uint8_t> bytes,
                                   std::vector<std::uint8_t>& echo) const;

 private:
  GateKey token_;
  std::uint64_t nonce_;
};

/// The proof of the token for a cookie: SipHash-2-4 under the token of (2, nonce, window, mac).
[[nodiscard]] std::uint64_t token_proof(const GateKey& token, std::uint64_t nonce,
                                        std::uint32_t window, std::uint64_t cookie_mac);
/// The host's proof of the token on its cookie: SipHash-2-4 under the token of (3, nonce,
/// window, mac) (another first byte than the joiner's token_proof, so neither stands for the
/// other).
/// The echo of a well-formed cookie (cookie_bytes) with the proof of `token`, whether or not the
/// cookie proves that token (JoinerGate echoes only one that does); nullopt for anything else.
[[nodiscard]] std::optional<std::vector<std::uint8_t>> echo_of_cookie(
    const GateKey& token, std::span<const std::uint8_t> cookie);
[[nodiscard]] std::uint64_t host_proof(const GateKey& token, std::uint64_t nonce,
                                       std::uint32_t window, std::uint64_t cookie_mac);

}  // namespace fixstep::net
