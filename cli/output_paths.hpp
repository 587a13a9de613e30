// The paths of each fixstep command: what it reads and what it writes, checked before any work
// (fixstep/io/output_paths.hpp: no output may be an input, nor two outputs one file).
#pragma once

#include <fixstep/io/output_paths.hpp>
#include <string>

#include "commands.hpp"
#include "compare.hpp"

namespace fixstep::cli {

/// The paths of one fixstep command (program "fixstep CMD").
using CommandPaths = OutputPaths;

/// check_output_paths(paths): see fixstep/io/output_paths.hpp.
inline void check_paths(const CommandPaths& paths) {
  check_output_paths(paths);
}

/// The paths of `run`, `render` (`scene` the file it will load: SCENE or the recording's),
/// `compare` and `view`, for check_paths.
[[nodiscard]] CommandPaths run_paths(const RunOptions& o);
[[nodiscard]] CommandPaths render_paths(const RenderOptions& o, const std::string& scene);
[[nodiscard]] CommandPaths compare_paths(const CompareOptions& o);
[[nodiscard]] CommandPaths view_paths(const ViewOptions& o);

}  // namespace fixstep::cli
