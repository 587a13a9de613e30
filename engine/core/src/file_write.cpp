// The atomic file write shared by recordings and scene files (file_write.hpp).
#include "fixstep/file_write.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <system_error>

namespace fixstep {

void write_file_atomically(const std::filesystem::path& file, std::string_view text) {
  const std::filesystem::path dir = file.has_parent_path() ? file.parent_path() : ".";
  const std::string tmp =
      (dir / fmt::format(".{}.tmp.{}", file.filename().string(), ::getpid())).string();
  auto fail = [&](int err) {
    ::unlink(tmp.c_str());
    std::error_code ec;
    if (err == ENOENT && !std::filesystem::is_directory(dir, ec)) {
      throw std::runtime_error(fmt::format("cannot write {}: the directory {} does not exist",
                                           file.string(), dir.string()));
    }
    throw std::runtime_error(fmt::format("cannot write {}: {}", file.string(), std::strerror(err)));
  };
  std::FILE* out = std::fopen(tmp.c_str(), "wbe");
  if (!out) fail(errno);
  errno = 0;
  const bool written = std::fwrite(text.data(), 1, text.size(), out) == text.size() &&
                       std::fflush(out) == 0 && !std::ferror(out);
  const int write_err = errno ? errno : EIO;
  if (std::fclose(out) != 0 || !written) fail(written ? (errno ? errno : EIO) : write_err);
  if (::rename(tmp.c_str(), file.c_str()) != 0) fail(errno);
}

}  // namespace fixstep
