// SIGXFSZ and SIGPIPE ignored where they would kill (write_signals.hpp).
#include "fixstep/io/write_signals.hpp"

#include <csignal>

namespace fixstep {

namespace {
/// Ignores `signal` unless the program installed a handler (or ignores it already).
void ignore_if_default(int signal) noexcept {
  struct sigaction current {};
  if (::sigaction(signal, nullptr, &current) != 0 || current.sa_handler != SIG_DFL) return;
  struct sigaction ignore {};
  ignore.sa_handler = SIG_IGN;
  sigemptyset(&ignore.sa_mask);
  ::sigaction(signal, &ignore, nullptr);
}
}  // namespace

void ignore_file_size_signal() noexcept {
#ifdef SIGXFSZ
  ignore_if_default(SIGXFSZ);
#endif
}

void ignore_write_signals() noexcept {
  ignore_file_size_signal();
#ifdef SIGPIPE
  ignore_if_default(SIGPIPE);
#endif
}

}  // namespace fixstep
