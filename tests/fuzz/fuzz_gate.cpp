// libFuzzer target: arbitrary bytes as a sequence of datagrams, joiners' exchanges and replays
// to a match host's gate, the state machine before any handshake (fixstep/net/net_gate.hpp);
// what it checks: gate_check.hpp. Built with the asan and fuzz presets; run as in
// docs/ROBUSTNESS.md, "Fuzzing".
#include <cstddef>
#include <cstdint>
#include <span>

#include "gate_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fixstep::fuzz::check_gate_datagrams(std::span<const std::uint8_t>(data, size));
  return 0;
}
