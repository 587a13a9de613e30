// What the running command is doing (command_phase.hpp).
#include "command_phase.hpp"

#include <atomic>

namespace fixstep::cli {

namespace {
std::atomic<const char*> command{"fixstep"};
std::atomic<const char*> phase{"starting"};
}  // namespace

void set_command(const char* name) noexcept {
  command.store(name);
  phase.store("starting");
}

void set_phase(const char* name) noexcept {
  phase.store(name);
}

const char* command_name() noexcept {
  return command.load();
}

const char* phase_name() noexcept {
  return phase.load();
}

}  // namespace fixstep::cli
