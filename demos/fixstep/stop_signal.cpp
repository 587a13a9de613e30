#include "stop_signal.hpp"

#include <csignal>

namespace fixstep::cli {

namespace {
volatile std::sig_atomic_t stop_signal = 0;
extern "C" void request_stop(int signal) {
  stop_signal = signal;
}
}  // namespace

StopOnSignal::StopOnSignal() {
  stop_signal = 0;
  previous_int_ = std::signal(SIGINT, request_stop);
  previous_term_ = std::signal(SIGTERM, request_stop);
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
