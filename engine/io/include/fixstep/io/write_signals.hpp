// The signals a write can raise, turned into errors a writer reports: SIGXFSZ (a file grown
// past the file-size limit, `ulimit -f`) and SIGPIPE (a pipe whose reader has gone). By
// default either kills the process without a word, leaving its temporary files behind; ignored,
// the write fails with EFBIG or EPIPE instead, and the writer reports "cannot write FILE: File
// too large" and removes its temporary file. One policy for every program built on fixstep.
#pragma once

namespace fixstep {

/// Ignores SIGXFSZ if its disposition is the default (a handler the program installed is
/// kept), so that a write past RLIMIT_FSIZE fails with EFBIG. Every output fixstep opens
/// (AtomicOutput, and through it every file it writes; VideoWriter) calls this first, so a
/// program that writes only through fixstep needs no call of its own. Idempotent;
/// process-wide, as signal dispositions are.
void ignore_file_size_signal() noexcept;

/// ignore_file_size_signal(), and SIGPIPE ignored likewise, so that writing to a pipe whose
/// reader has gone fails with EPIPE instead of killing the process. For programs that check
/// every write, standard output included (the fixstep command, state_hashes): a program that
/// ignores its write errors would, with SIGPIPE ignored, keep writing into a closed pipe, so
/// fixstep never ignores SIGPIPE on a program's behalf.
void ignore_write_signals() noexcept;

}  // namespace fixstep
