// Results printed on standard output (a summary, a verdict) must not be lost without a word: a
// full disk (`>/dev/full`), a closed descriptor (`>&-`) or a write error makes the program exit
// non-zero with a message on standard error instead of 0.
#pragma once

#include <functional>
#include <string>
#include <string_view>

namespace fixstep {

/// Whether descriptor 1 is open. A program that prints its results there checks this before it
/// starts (and refuses to run when it is closed): a file it opened later would otherwise take
/// descriptor 1, and the results printed would be written into it.
[[nodiscard]] bool standard_output_is_open() noexcept;

/// Flushes stdout and returns "" when everything printed on it was written, else why not: the
/// system's reason ("No space left on device", "Bad file descriptor", "Broken pipe" when
/// SIGPIPE is ignored), or "a write failed" when an earlier write failed and its reason is gone.
[[nodiscard]] std::string standard_output_failure();

/// Runs `body` (a program's work, returning its exit status) with its results on standard
/// output checked: when descriptor 1 is closed, `body` is not run ("PROGRAM: error: standard
/// output is closed: ..." on standard error, status 1); when printing failed
/// (standard_output_failure), "PROGRAM: error: cannot write the results to standard output:
/// REASON" on standard error and status 1, or body's status when that is already non-zero.
[[nodiscard]] int with_results_on_standard_output(std::string_view program,
                                                  const std::function<int()>& body);

}  // namespace fixstep
