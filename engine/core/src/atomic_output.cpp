// A file streamed into a temporary file and renamed into place (atomic_output.hpp).
#include "fixstep/atomic_output.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <system_error>
#include <utility>

namespace fixstep {

namespace {
std::filesystem::path directory_of(const std::filesystem::path& file) {
  return file.has_parent_path() ? file.parent_path() : std::filesystem::path(".");
}
}  // namespace

AtomicOutput::AtomicOutput(std::filesystem::path file)
    : file_(std::move(file)),
      tmp_((directory_of(file_) / fmt::format(".{}.tmp.{}", file_.filename().string(), ::getpid()))
               .string()) {
  out_ = std::fopen(tmp_.c_str(), "wbe");
  if (!out_) fail(errno);
}

AtomicOutput::~AtomicOutput() {
  if (out_) {
    std::fclose(out_);
    ::unlink(tmp_.c_str());
  }
}

void AtomicOutput::fail(int err) {
  if (out_) std::fclose(out_), out_ = nullptr;
  ::unlink(tmp_.c_str());
  const std::filesystem::path dir = directory_of(file_);
  std::error_code ec;
  if (err == ENOENT && !std::filesystem::is_directory(dir, ec)) {
    throw std::runtime_error(fmt::format("cannot write {}: the directory {} does not exist",
                                         file_.string(), dir.string()));
  }
  throw std::runtime_error(fmt::format("cannot write {}: {}", file_.string(), std::strerror(err)));
}

void AtomicOutput::append(std::string_view text) {
  if (!out_) throw std::logic_error("AtomicOutput::append after commit");
  errno = 0;
  if (std::fwrite(text.data(), 1, text.size(), out_) != text.size()) fail(errno ? errno : EIO);
  size_ += text.size();
}

void AtomicOutput::commit() {
  if (!out_) throw std::logic_error("AtomicOutput::commit twice");
  errno = 0;
  const bool flushed = std::fflush(out_) == 0 && !std::ferror(out_);
  const int flush_err = errno ? errno : EIO;
  std::FILE* out = std::exchange(out_, nullptr);
  if (std::fclose(out) != 0 || !flushed) {
    out_ = nullptr;
    fail(flushed ? (errno ? errno : EIO) : flush_err);
  }
  if (::rename(tmp_.c_str(), file_.c_str()) != 0) fail(errno);
}

}  // namespace fixstep
