// The ".NAME.tmp.PID" files an atomic write leaves when its process is killed (kill -9, power
// loss): found, and removed once provably stale.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace fixstep {

/// A temporary file's name taken apart: ".frames.csv.tmp.4242" is {"frames.csv", 4242}.
struct TemporaryName {
  std::string target;  ///< the file it was to be renamed onto, e.g. "frames.csv"
  long pid = 0;        ///< the process that was writing it
};

/// ".NAME.tmp.PID", the temporary beside NAME that write_file_atomically, AtomicFile and
/// VideoWriter write before renaming it onto NAME; std::nullopt for any other file name.
[[nodiscard]] std::optional<TemporaryName> parse_temporary_name(std::string_view filename);

/// Whether process `pid` is running (kill(pid, 0) is not ESRCH). A process of another user
/// counts as running (EPERM), so its files are never taken for stale.
[[nodiscard]] bool process_running(long pid);

/// Removes the temporaries in `dir` whose target `ours` accepts and whose process is no longer
/// running: they can only be left by a killed run, never renamed by anyone again. Another
/// program's ".x.tmp.N" (a target `ours` rejects) and a running process's are kept. A PID
/// reused since by an unrelated process keeps its file (the safe side). A missing or unreadable
/// `dir`, or a file that cannot be removed, is skipped without error. Returns the paths removed.
std::vector<std::filesystem::path> remove_stale_temporaries(
    const std::filesystem::path& dir, const std::function<bool(std::string_view)>& ours);

}  // namespace fixstep
