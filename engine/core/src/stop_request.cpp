#include "fixstep/core/stop_request.hpp"

#include <atomic>
#include <string>

namespace fixstep {

namespace {

std::atomic<int> pending_stop{0};
static_assert(std::atomic<int>::is_always_lock_free, "request_stop must be async-signal-safe");
thread_local const std::atomic<int>* thread_stop = nullptr;  ///< the innermost StopScope's

}  // namespace

StopRequested::StopRequested(int signal)
    : std::runtime_error("stopped on request (signal " + std::to_string(signal) + ")"),
      signal_(signal) {}

void request_stop(int signal) noexcept {
  pending_stop.store(signal, std::memory_order_relaxed);
}

int stop_requested() noexcept {
  if (const int signal = pending_stop.load(std::memory_order_relaxed)) return signal;
  return thread_stop ? thread_stop->load(std::memory_order_relaxed) : 0;
}

void clear_stop_request() noexcept {
  pending_stop.store(0, std::memory_order_relaxed);
}

void throw_if_stop_requested() {
  if (const int signal = stop_requested(); signal != 0) throw StopRequested(signal);
}

StopScope::StopScope(const std::atomic<int>& flag) noexcept : previous_(thread_stop) {
  thread_stop = &flag;
}

StopScope::~StopScope() {
  thread_stop = previous_;
}

}  // namespace fixstep
