// Before any work: no output of a program may be one of its inputs, nor two outputs one file,
// nor a directory, a socket or a descriptor not open for writing; a capture directory holds one
// capture; stale temporaries of killed runs are removed. The checks of every fixstep command and
// of every game (fixstep::app::run, fixstep::net::run).
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace fixstep {

/// A command line whose paths a program refuses: what() is the whole message, "PROGRAM: ...".
/// Programs print it and exit 2 (a command-line error).
class PathRefused : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A path and the option (or argument) that gave it, for messages: {"--csv", "out.csv"}.
struct NamedPath {
  std::string role;  ///< "SCENE", "--input", "--csv", "--out (DIR/frames.csv)", ...
  std::string path;
};

/// The paths of one run of a program: what it reads, the files it writes, and its capture
/// directory.
struct OutputPaths {
  std::string program;  ///< the messages' first words: "fixstep run", "peggle"
  std::vector<NamedPath> inputs{};
  std::vector<NamedPath> outputs{};
  /// --out DIR of a capture (frame_NNNNNN.png and its frames.csv manifest)
  std::optional<std::string> capture_dir{};
  bool overwrite = false;  ///< --overwrite: the old capture in DIR goes
};

/// Throws PathRefused when an output is a directory, a block device, a socket or another
/// special file, or names a descriptor not open for writing (output_refusal); when an output is
/// the same file as an input, or two outputs are one file, compared by device and inode (a
/// symbolic or hard link, "./x" and "x" are caught); an output that does not exist yet is its
/// directory's identity and name. Every existing capture file in `capture_dir` counts as an
/// output (a frame is rewritten, --overwrite removes them all). Also throws when `capture_dir`
/// already holds a capture and `overwrite` is not set (capture_dir_refusal). Inputs that do not
/// exist are skipped: reading them reports it. Then removes the stale ".NAME.tmp.PID" files of
/// the outputs (remove_stale_temporaries).
void check_output_paths(const OutputPaths& paths);

/// `message` with the option that gave the file put first, when it is a write error ("cannot
/// write PATH: REASON") of an output of `paths` or of a file in its capture directory:
/// "--csv: cannot write out.csv: File too large", "--out: cannot write d/frame_000003.png:
/// ...". std::nullopt for any other message.
[[nodiscard]] std::optional<std::string> naming_the_option(const OutputPaths& paths,
                                                           std::string_view message);

/// Whether an output of `paths` writes into standard output: it is named so ("-",
/// "/dev/stdout", "/dev/fd/1", "/proc/self/fd/1") or it is the FIFO or device that
/// descriptor 1 is open on (compared by device and inode). A program whose data goes there
/// (`fixstep run s.toml --csv -`, `peggle --frames 60 --record -`) prints its summary lines on
/// standard error instead (keep_standard_output_for_data), so standard output holds the data
/// alone, unmixed.
[[nodiscard]] bool data_on_standard_output(const OutputPaths& paths);

/// Keeps standard output for the data: descriptor 1 is duplicated, the names of standard
/// output stand for the duplicate from now on (set_standard_output_descriptor), and descriptor
/// 1 becomes a duplicate of descriptor 2, so everything printed to stdout goes to standard
/// error. When descriptor 1 is not open nothing changes (writing the data then says so).
void keep_standard_output_for_data();

}  // namespace fixstep
