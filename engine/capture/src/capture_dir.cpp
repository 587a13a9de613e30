// A capture directory made ready for a new capture (fixstep/capture/capture_dir.hpp).
#include "fixstep/capture/capture_dir.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <system_error>
#include <vector>

#include "fixstep/capture/capture.hpp"
#include "fixstep/io/capture_files.hpp"
#include "fixstep/io/stale_temporaries.hpp"

namespace fixstep {

void prepare_capture_dir(const std::filesystem::path& dir, bool overwrite) {
  prepare_output_dir(dir);
  remove_stale_temporaries(dir, is_capture_file);
  if (!overwrite) return;
  std::vector<std::filesystem::path> old = capture_files_in(dir);
  // The manifests first: a directory with frames and no frames.csv reads as unfinished.
  std::stable_partition(old.begin(), old.end(),
                        [](const auto& f) { return !f.filename().string().starts_with("frame_"); });
  for (const std::filesystem::path& f : old) {
    std::error_code ec;
    std::filesystem::remove(f, ec);
    if (ec) {
      throw CaptureError(fmt::format("--overwrite: cannot remove {} of the old capture: {}",
                                     f.string(), ec.message()));
    }
  }
}

}  // namespace fixstep
