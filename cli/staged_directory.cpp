// A directory renamed into place only when complete (staged_directory.hpp).
#include "staged_directory.hpp"

#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <stdexcept>
#include <system_error>

namespace fixstep::cli {

namespace fs = std::filesystem;

namespace {
[[noreturn]] void cannot_create(const fs::path& dir, int err) {
  throw std::runtime_error(fmt::format("cannot create {}: {}", dir.string(),
                                       std::error_code(err, std::generic_category()).message()));
}

fs::path parent_of(const fs::path& target) {
  const fs::path p = target.lexically_normal();
  const fs::path parent = (p.has_filename() ? p : p.parent_path()).parent_path();
  return parent.empty() ? fs::path(".") : parent;
}

fs::path name_of(const fs::path& target) {
  const fs::path p = target.lexically_normal();
  return (p.has_filename() ? p : p.parent_path()).filename();
}
}  // namespace

StagedDirectory::StagedDirectory(fs::path target) : target_(std::move(target)) {
  create_parents();
  staging_ = parent_of(target_) / fmt::format(".{}.tmp.{}", name_of(target_).string(), ::getpid());
  std::error_code ec;
  fs::remove_all(staging_, ec);  // a killed run's of this PID (not ours: we are this PID)
  if (::mkdir(staging_.c_str(), 0777) != 0) {
    const int err = errno;
    staging_.clear();
    cannot_create(target_, err);
  }
  struct stat st {};
  if (::stat(target_.c_str(), &st) == 0) (void)::chmod(staging_.c_str(), st.st_mode & 07777);
}

void StagedDirectory::create_parents() {
  std::vector<fs::path> missing;
  std::error_code ec;
  for (fs::path p = parent_of(target_); !p.empty() && !fs::exists(fs::symlink_status(p, ec));
       p = p.parent_path()) {
    missing.push_back(p);
    if (p == p.parent_path()) break;
  }
  for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
    if (::mkdir(it->c_str(), 0777) != 0) cannot_create(*it, errno);
    created_.push_back(*it);
  }
}

StagedDirectory::~StagedDirectory() {
  if (published_) return;
  std::error_code ec;
  if (!staging_.empty()) fs::remove_all(staging_, ec);
  for (auto it = created_.rbegin(); it != created_.rend(); ++it) ::rmdir(it->c_str());
}

void StagedDirectory::publish() {
  if (::rename(staging_.c_str(), target_.c_str()) != 0) {
    const int err = errno;
    throw std::runtime_error(fmt::format("cannot create {}: {}", target_.string(),
                                         std::error_code(err, std::generic_category()).message()));
  }
  published_ = true;
}

}  // namespace fixstep::cli
