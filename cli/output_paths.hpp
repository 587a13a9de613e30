// Before any work: no output of a command may be one of its inputs, nor two outputs one file;
// a capture directory holds one capture; stale temporaries of killed runs are removed.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "commands.hpp"
#include "compare.hpp"

namespace fixstep::cli {

/// A command line whose paths fixstep refuses: what() is the whole message, "fixstep CMD:
/// ...". main prints it and exits 2 (a command-line error).
class PathRefused : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A path and the option (or argument) that gave it, for messages: {"--csv", "out.csv"}.
struct NamedPath {
  std::string role;  ///< "SCENE", "--input", "--csv", "--out (DIR/frames.csv)", ...
  std::string path;
};

/// The paths of one command: what it reads, the files it writes, and its capture directory.
struct CommandPaths {
  std::string command;  ///< "run", "render", ...
  std::vector<NamedPath> inputs;
  std::vector<NamedPath> outputs;
  std::optional<std::string> capture_dir;  ///< --out DIR of render and compare
  bool overwrite = false;                  ///< --overwrite: the old capture in DIR goes
};

/// Throws PathRefused when an output is the same file as an input, or two outputs are one
/// file, compared by device and inode (a symbolic or hard link, "./x" and "x" are caught); an
/// output that does not exist yet is its directory's identity and name. Every existing capture
/// file in `capture_dir` counts as an output (a frame is rewritten, --overwrite removes them
/// all). Also throws when `capture_dir` already holds a capture and `overwrite` is not set
/// (capture_dir_refusal). Inputs that do not exist are skipped: reading them reports it.
/// Then removes the stale ".NAME.tmp.PID" files of the outputs (remove_stale_temporaries).
void check_paths(const CommandPaths& paths);

/// `message` with the option that gave the file put first, when it is a write error ("cannot
/// write PATH: REASON") of an output of `paths` or of a file in its capture directory:
/// "--csv: cannot write out.csv: File too large", "--out: cannot write d/frame_000003.png:
/// ...". std::nullopt for any other message.
[[nodiscard]] std::optional<std::string> naming_the_option(const CommandPaths& paths,
                                                           std::string_view message);

/// The paths of `run`, `render` (`scene` the file it will load: SCENE or the recording's),
/// `compare` and `view`, for check_paths.
[[nodiscard]] CommandPaths run_paths(const RunOptions& o);
[[nodiscard]] CommandPaths render_paths(const RenderOptions& o, const std::string& scene);
[[nodiscard]] CommandPaths compare_paths(const CompareOptions& o);
[[nodiscard]] CommandPaths view_paths(const ViewOptions& o);

}  // namespace fixstep::cli
