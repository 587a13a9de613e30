// Results on standard output, checked (fixstep/io/standard_output.hpp).
#include "fixstep/io/standard_output.hpp"

#include <fcntl.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace fixstep {

bool standard_output_is_open() noexcept {
  return ::fcntl(1, F_GETFL) >= 0;
}

std::string standard_output_failure() {
  const bool failed_before = std::ferror(stdout) != 0;
  errno = 0;
  if (std::fflush(stdout) != 0 && errno != 0) return std::strerror(errno);
  if (failed_before || std::ferror(stdout) != 0) return "a write failed";
  return {};
}

int with_results_on_standard_output(std::string_view program, const std::function<int()>& body) {
  const std::string name(program);
  if (!standard_output_is_open()) {  // a file opened later would take descriptor 1
    std::fprintf(stderr,
                 "%s: error: standard output is closed: the results printed there would be "
                 "lost (nothing was run); redirect it to a file, or to /dev/null to discard "
                 "them\n",
                 name.c_str());
    return 1;
  }
  const int status = body();
  if (const std::string why = standard_output_failure(); !why.empty()) {
    std::fprintf(stderr, "%s: error: cannot write the results to standard output: %s\n",
                 name.c_str(), why.c_str());
    return status != 0 ? status : 1;
  }
  return status;
}

}  // namespace fixstep
