// Standard output kept for a command's data (standard_output.hpp).
#include "standard_output.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <fixstep/io/output_target.hpp>

namespace fixstep::cli {

namespace {
/// Whether `target` (a stream opened by path) is the file descriptor 1 is open on.
bool same_as_descriptor_1(const OutputTarget& target) {
  struct stat out {
  }, st{};
  return ::fstat(1, &out) == 0 && ::stat(target.path.c_str(), &st) == 0 &&
         (S_ISFIFO(st.st_mode) || S_ISCHR(st.st_mode)) && st.st_dev == out.st_dev &&
         st.st_ino == out.st_ino;
}
}  // namespace

bool data_on_standard_output(const CommandPaths& paths) {
  for (const NamedPath& out : paths.outputs) {
    const OutputTarget target = classify_output(out.path);
    if (target.kind != OutputKind::stream) continue;
    if (target.fd == standard_output_descriptor()) return true;
    if (target.fd < 0 && same_as_descriptor_1(target)) return true;
  }
  return false;
}

void keep_standard_output_for_data() {
  std::fflush(stdout);
  const int data = ::fcntl(1, F_DUPFD_CLOEXEC, 10);
  if (data < 0) return;  // not open: the data's writer reports it
  set_standard_output_descriptor(data);
  ::dup2(2, 1);
}

}  // namespace fixstep::cli
