// Stale ".NAME.tmp.PID" files of killed runs (stale_temporaries.hpp).
#include "fixstep/io/stale_temporaries.hpp"

#include <cerrno>
#include <charconv>
#include <csignal>  // kill (POSIX, declared by glibc's <signal.h>)
#include <system_error>

namespace fixstep {

std::optional<TemporaryName> parse_temporary_name(std::string_view name) {
  constexpr std::string_view infix = ".tmp.";
  if (name.size() < 2 || name[0] != '.') return std::nullopt;
  const std::size_t at = name.rfind(infix);
  if (at == std::string_view::npos || at < 2) return std::nullopt;  // NAME is not empty
  const std::string_view digits = name.substr(at + infix.size());
  long pid = 0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), pid);
  if (digits.empty() || ec != std::errc() || end != digits.data() + digits.size() || pid <= 0) {
    return std::nullopt;
  }
  return TemporaryName{.target = std::string(name.substr(1, at - 1)), .pid = pid};
}

bool process_running(long pid) {
  if (pid <= 0) return true;  // not a PID we could have written: keep its file
  return ::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH;
}

std::vector<std::filesystem::path> remove_stale_temporaries(
    const std::filesystem::path& dir, const std::function<bool(std::string_view)>& ours) {
  std::vector<std::filesystem::path> removed;
  std::error_code ec;
  std::filesystem::directory_iterator it(dir.empty() ? "." : dir, ec);
  for (const std::filesystem::directory_iterator end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    const std::optional<TemporaryName> tmp = parse_temporary_name(name);
    if (!tmp || !ours(tmp->target) || process_running(tmp->pid)) continue;
    std::error_code rm;
    if (!it->is_directory(rm) && std::filesystem::remove(it->path(), rm)) {
      removed.push_back(it->path());
    }
  }
  return removed;
}

}  // namespace fixstep
