// fixstep::io, all of it: files, atomic outputs, recordings as files and text, signals, limits.
// One include for a program that uses the whole library; each header below stands alone.
#pragma once

#include "fixstep/io/atomic_output.hpp"
#include "fixstep/io/capture_files.hpp"
#include "fixstep/io/command_limits.hpp"
#include "fixstep/io/file_read.hpp"
#include "fixstep/io/file_write.hpp"
#include "fixstep/io/output_paths.hpp"
#include "fixstep/io/output_target.hpp"
#include "fixstep/io/printable.hpp"
#include "fixstep/io/recording_file.hpp"
#include "fixstep/io/recording_writer.hpp"
#include "fixstep/io/stale_temporaries.hpp"
#include "fixstep/io/standard_output.hpp"
#include "fixstep/io/stop_signal.hpp"
#include "fixstep/io/summary.hpp"
#include "fixstep/io/write_signals.hpp"
