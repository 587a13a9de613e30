#include "stop_signal.hpp"

#include <csignal>

#include "fixstep/core/stop_request.hpp"

namespace fixstep::cli {

namespace {
volatile std::sig_atomic_t stop_signal = 0;
extern "C" void on_stop_signal(int signal) {
  stop_signal = signal;
  fixstep::request_stop(signal);  // also seen by the engine's long loops inside a tick
}
}  // namespace

StopOnSignal::StopOnSignal() {
  stop_signal = 0;
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

}  // namespace fixstep::cli
