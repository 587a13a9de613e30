// For gtests that run the `fixstep` program (FIXSTEP_CLI, its path, set by tests/CMakeLists.txt)
// and read what it wrote.
#pragma once

#include <fmt/format.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace fixstep::testing {

/// Runs `fixstep ARGS` (a shell word list; quote paths) with stdout and stderr into `out`;
/// returns its exit status, or -1 when it did not exit (a signal).
inline int fixstep_cli(const std::string& args, const std::filesystem::path& out) {
  const int status =
      std::system(fmt::format("'{}' {} > '{}' 2>&1", FIXSTEP_CLI, args, out.string()).c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/// The whole text of `file` ("" if it cannot be read).
inline std::string text_of(const std::filesystem::path& file) {
  std::ifstream in(file);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace fixstep::testing
