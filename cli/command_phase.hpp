// What the running command is doing, for the message of an allocation that fails although the
// command's memory estimate (command_memory.hpp) allowed it: "fixstep: error: render: out of
// memory while building the world". Set from any thread (a view's load runs on its own).
#pragma once

namespace fixstep::cli {

/// Names the command ("run", "render", ...) before it starts; its phase is "starting".
void set_command(const char* command) noexcept;
/// Names what the command does from now on, e.g. "loading the scene" (a string literal: only the
/// pointer is kept).
void set_phase(const char* phase) noexcept;

/// The command and phase last named (for main's message of a std::bad_alloc).
[[nodiscard]] const char* command_name() noexcept;
[[nodiscard]] const char* phase_name() noexcept;

}  // namespace fixstep::cli
