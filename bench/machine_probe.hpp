// What a benchmark report says of the machine while it ran: the load average, and how far
// apart its first two CPUs are. Two threads hand each other the cache lines one writes and the
// other reads; the time a line takes to go over and back sets what a second thread can gain,
// and on a virtual machine it changes when the host moves the vCPUs (docs/perf/
// contact_solver_plan.md has the figures). Linux only, as the benchmarks are.
#pragma once

#include <fmt/format.h>
#include <pthread.h>
#include <sched.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include "median.hpp"

namespace fixstep::bench {

/// The 1-minute load average, or NaN where the system does not give it.
inline double load_average() {
  double load[1] = {0.0};
  return getloadavg(load, 1) == 1 ? load[0] : std::nan("");
}

namespace machine_probe_detail {

inline bool pin_to(int cpu) {
  cpu_set_t set;
  CPU_ZERO(&set);
  CPU_SET(cpu, &set);
  return pthread_setaffinity_np(pthread_self(), sizeof set, &set) == 0;
}

/// Spins until `line` holds `want`; false once `deadline` passed (the other thread not run)
/// or the other thread set `failed`.
inline bool wait_for(const std::atomic<long>& line, long want,
                     std::chrono::steady_clock::time_point deadline,
                     const std::atomic<bool>& failed) {
  for (unsigned spins = 1; line.load(std::memory_order_acquire) != want; ++spins) {
    if (spins % 4096 == 0 && (failed || std::chrono::steady_clock::now() > deadline)) {
      return false;
    }
  }
  return true;
}

}  // namespace machine_probe_detail

/// The round trip of one cache line between a thread on the process's first allowed CPU and
/// one on its second, ns: the median of 5 batches of 2000 round trips (each thread writes the
/// line the other waits for). NaN where the process may run on fewer than two CPUs, pinning is
/// refused, or the batches have not ended within 5 s (a vCPU not run). Takes a few
/// milliseconds; the caller's thread keeps the affinity it had.
inline double core_round_trip_ns() {
  namespace d = machine_probe_detail;
  using Clock = std::chrono::steady_clock;
  cpu_set_t allowed, before;
  if (sched_getaffinity(0, sizeof allowed, &allowed) != 0) return std::nan("");
  if (pthread_getaffinity_np(pthread_self(), sizeof before, &before) != 0) return std::nan("");
  std::vector<int> cpus;
  for (int c = 0; c < CPU_SETSIZE && cpus.size() < 2; ++c) {
    if (CPU_ISSET(c, &allowed)) cpus.push_back(c);
  }
  if (cpus.size() < 2) return std::nan("");
  constexpr long trips = 2000;
  constexpr int batches = 5;
  alignas(64) std::atomic<long> line{0};
  std::atomic<bool> failed{false};
  const Clock::time_point deadline = Clock::now() + std::chrono::seconds(batches);
  std::thread other([&] {
    if (!d::pin_to(cpus[1])) failed = true;
    for (long i = 0; i < batches * trips && !failed; ++i) {
      if (!d::wait_for(line, 2 * i + 1, deadline, failed)) failed = true;
      line.store(2 * i + 2, std::memory_order_release);
    }
  });
  std::vector<double> ns;
  if (!d::pin_to(cpus[0])) failed = true;
  for (int b = 0; b < batches && !failed; ++b) {
    const Clock::time_point start = Clock::now();
    for (long i = b * trips; i < (b + 1) * trips && !failed; ++i) {
      line.store(2 * i + 1, std::memory_order_release);
      if (!d::wait_for(line, 2 * i + 2, deadline, failed)) failed = true;
    }
    ns.push_back(std::chrono::duration<double, std::nano>(Clock::now() - start).count() / trips);
  }
  other.join();
  pthread_setaffinity_np(pthread_self(), sizeof before, &before);
  return failed || ns.empty() ? std::nan("") : median(ns);
}

/// The report's sentence on the round trips measured at a run's start and end (ns, NaN where
/// not measured), with what it means for the rows on two threads.
inline std::string round_trip_sentence(double start, double end) {
  auto ns = [](double v) {
    return std::isnan(v) ? std::string("not measured") : fmt::format("{:.0f} ns", v);
  };
  return fmt::format(
      " A cache line's round trip between the first two CPUs: {} at the start, {} at the end "
      "(two threads pay it for each line one hands the other; on a virtual machine it changes "
      "when the host moves the vCPUs).",
      ns(start), ns(end));
}

}  // namespace fixstep::bench
