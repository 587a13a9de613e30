// A directory built whole or not at all: its files are written into a temporary directory
// beside it, which is renamed into place only when complete (`fixstep new`).
#pragma once

#include <filesystem>
#include <vector>

namespace fixstep::cli {

/// Creates the missing parents of `target` and a temporary directory ".NAME.tmp.PID" beside
/// it, to be filled through path() and renamed onto `target` by publish(). Destroyed without
/// publish() (an error, an exception, a stop request), it removes the temporary directory with
/// everything in it and the parents it created, leaving the file system as it found it.
/// `target` must not exist or be an empty directory (the caller checks); an empty directory is
/// replaced by the finished one, which takes its permission bits. Throws std::runtime_error
/// "cannot create DIR: REASON" when a directory cannot be created.
class StagedDirectory {
 public:
  explicit StagedDirectory(std::filesystem::path target);
  ~StagedDirectory();
  StagedDirectory(const StagedDirectory&) = delete;
  StagedDirectory& operator=(const StagedDirectory&) = delete;

  /// The temporary directory to write into.
  [[nodiscard]] const std::filesystem::path& path() const { return staging_; }
  /// Renames the temporary directory onto the target. Throws std::runtime_error naming the
  /// target when it cannot (the destructor then removes everything).
  void publish();

 private:
  void create_parents();
  std::filesystem::path target_;
  std::filesystem::path staging_;
  std::vector<std::filesystem::path> created_;  // parents made here, outermost first
  bool published_ = false;
};

}  // namespace fixstep::cli
