// A command whose data goes to standard output (`fixstep run s.toml --csv - | head`): its
// summary lines and paths go to standard error instead, so standard output holds the data
// alone, unmixed.
#pragma once

#include "output_paths.hpp"

namespace fixstep::cli {

/// Whether an output of `paths` writes into standard output: it is named so ("-",
/// "/dev/stdout", "/dev/fd/1", "/proc/self/fd/1") or it is the FIFO or device that
/// descriptor 1 is open on (compared by device and inode).
[[nodiscard]] bool data_on_standard_output(const CommandPaths& paths);

/// Keeps standard output for the data: descriptor 1 is duplicated, the names of standard
/// output stand for the duplicate from now on (set_standard_output_descriptor), and descriptor
/// 1 becomes a duplicate of descriptor 2, so everything printed to stdout goes to standard
/// error. When descriptor 1 is not open nothing changes (writing the data then says so).
void keep_standard_output_for_data();

}  // namespace fixstep::cli
