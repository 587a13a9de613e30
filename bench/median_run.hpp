// Which Google Benchmark runs the benchmarks' reporters keep: the median of repeated runs, or
// the single run when a case is not repeated.
#pragma once

#include <benchmark/benchmark.h>

namespace fixstep::bench {

/// True for a median aggregate, or a plain run of a case that is not repeated; false for
/// errors, other aggregates (mean, stddev) and the individual repetitions.
inline bool median_or_single(const benchmark::BenchmarkReporter::Run& r) {
  if (r.error_occurred) return false;
  const bool aggregate = r.run_type == benchmark::BenchmarkReporter::Run::RT_Aggregate;
  if (aggregate) return r.aggregate_name == "median";
  return r.repetitions <= 1;
}

}  // namespace fixstep::bench
