// The atomic file write shared by recordings and scene files (file_write.hpp): one AtomicOutput
// (atomic_output.hpp) written whole.
#include "fixstep/io/file_write.hpp"

#include "fixstep/io/atomic_output.hpp"

namespace fixstep {

void write_file_atomically(const std::filesystem::path& file, std::string_view text) {
  AtomicOutput out(file);
  out.append(text);
  out.commit();
}

}  // namespace fixstep
