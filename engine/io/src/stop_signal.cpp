#include "fixstep/io/stop_signal.hpp"

#include <csignal>

#include "fixstep/core/stop_request.hpp"

namespace fixstep {

namespace {
volatile std::sig_atomic_t stop_signal = 0;
volatile std::sig_atomic_t stop_ticks = 1;  // StopOnSignal's interrupt_ticks
extern "C" void on_stop_signal(int signal) {
  stop_signal = signal;
  if (stop_ticks != 0) fixstep::request_stop(signal);  // seen by the long loops inside a tick
}
}  // namespace

StopOnSignal::StopOnSignal(bool interrupt_ticks) {
  stop_signal = 0;
  stop_ticks = interrupt_ticks ? 1 : 0;
  clear_stop_request();
  previous_int_ = std::signal(SIGINT, on_stop_signal);
  previous_term_ = std::signal(SIGTERM, on_stop_signal);
}

StopOnSignal::~StopOnSignal() {
  std::signal(SIGINT, previous_int_);
  std::signal(SIGTERM, previous_term_);
}

int StopOnSignal::requested() {
  return stop_signal;
}

const char* StopOnSignal::name() {
  return stop_signal == SIGINT ? "SIGINT" : "SIGTERM";
}

}  // namespace fixstep
