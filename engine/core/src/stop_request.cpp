#include "fixstep/stop_request.hpp"

#include <atomic>
#include <string>

namespace fixstep {

namespace {

std::atomic<int> pending_stop{0};
static_assert(std::atomic<int>::is_always_lock_free, "request_stop must be async-signal-safe");

}  // namespace

StopRequested::StopRequested(int signal)
    : std::runtime_error("stopped on request (signal " + std::to_string(signal) + ")"),
      signal_(signal) {}

void request_stop(int signal) noexcept {
  pending_stop.store(signal, std::memory_order_relaxed);
}

int stop_requested() noexcept {
  return pending_stop.load(std::memory_order_relaxed);
}

void clear_stop_request() noexcept {
  pending_stop.store(0, std::memory_order_relaxed);
}

void throw_if_stop_requested() {
  if (const int signal = stop_requested(); signal != 0) throw StopRequested(signal);
}

}  // namespace fixstep
