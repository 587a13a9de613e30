// The check of the fuzz target fuzz_gate (and its regression test in test_net): arbitrary bytes
// as a sequence of datagrams to a match host's gate (fixstep/net/net_gate.hpp). Record format,
// each starting with one control byte c:
//   c & 3:        0 a raw datagram (next byte: its length, then its bytes), 1 a joiner's full
//                 exchange with the match's token, 2 with another token, 3 the last admitted
//                 echo again
//   (c >> 2) & 3: which of four addresses sends it (two IPv4 addresses, two ports each)
//   (c >> 4) & 1: whether ENet has a peer at that address
//   (c >> 5) & 7: how far the clock moves first (0, 1, 10, 100, 1000, 2500, 5000, 12000 ms)
// A finding (abort with a message) when: a reply is not smaller than its datagram; bytes out
// exceed bytes in; a datagram goes to ENet from an address neither connected nor admitted in
// the last two cookie windows; an address is admitted without a proof of the token; a replayed
// echo admits again; more addresses are admitted than max_admitted.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

namespace fixstep::fuzz {

void check_gate_datagrams(std::span<const std::uint8_t> bytes);

}  // namespace fixstep::fuzz
