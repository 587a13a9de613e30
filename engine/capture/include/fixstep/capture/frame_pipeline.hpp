// FramePipeline: hands frames from the drawing thread to one worker thread through a ring of
// buffers allocated up front; what FrameWriter (PNG) and VideoWriter (MP4, GIF) share.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <span>
#include <thread>
#include <vector>

namespace fixstep {

/// One producer, one worker: submit() copies a frame into one of `slots` buffers of
/// `frame_bytes` bytes each (allocated by the constructor: nothing is allocated per frame) and
/// returns at once; it blocks only while every buffer still waits for the worker. The worker
/// calls `consume(frame, tag)` for each submitted frame, once, in submission order; `tag` is the
/// number given to submit() (a frame number, a presentation timestamp).
///
/// Errors: the first exception `consume` throws stops the worker; that frame and every later one
/// are dropped, and submit(), drain() and stop() rethrow it from then on.
///
/// Thread safety: call every member from one thread (the producer); `consume` runs on the
/// worker and may touch what the producer leaves alone while frames are queued.
class FramePipeline {
 public:
  using Consumer = std::function<void(std::span<const std::uint8_t> frame, std::uint64_t tag)>;
  /// What stop() and the destructor do with frames still queued.
  enum class Pending { consume, drop };

  /// Allocates the buffers and starts the worker. Throws std::invalid_argument if frame_bytes
  /// or slots is 0, std::system_error if the thread cannot start.
  FramePipeline(std::size_t frame_bytes, std::size_t slots, Consumer consume,
                Pending at_destruction);
  /// Stops the worker as `at_destruction` says; never throws (an error is dropped: call stop()
  /// first to see it).
  ~FramePipeline();
  FramePipeline(const FramePipeline&) = delete;
  FramePipeline& operator=(const FramePipeline&) = delete;

  /// Queues a copy of `frame` with `tag`. Throws std::invalid_argument unless frame has
  /// frame_bytes bytes, std::logic_error after stop(), or the worker's error.
  void submit(std::span<const std::uint8_t> frame, std::uint64_t tag);
  /// Blocks until every submitted frame is consumed. Throws the worker's error if it failed.
  void drain();
  /// Consumes (Pending::consume) or drops the frames still queued, then joins the worker: from
  /// here on `consume` is never called and what it used is the producer's again. Throws the
  /// worker's error if it failed, now or earlier. Idempotent.
  void stop(Pending pending);
  /// Whether stop() has not run.
  [[nodiscard]] bool running() const { return worker_.joinable(); }
  /// The worker's error, if it failed (for a caller that reports it itself).
  [[nodiscard]] std::exception_ptr error() const;

 private:
  void work();

  std::size_t frame_bytes_;
  Consumer consume_;
  Pending at_destruction_;
  std::vector<std::vector<std::uint8_t>> slots_;  // the ring of frame buffers
  std::vector<std::uint64_t> tags_;               // the tag of the frame each slot holds

  // Shared with the worker, guarded by mutex_.
  mutable std::mutex mutex_;
  std::condition_variable queued_;    // worker waits: a frame was queued, or stop
  std::condition_variable released_;  // producer waits: a slot was freed, or the worker failed
  std::size_t head_ = 0;              // oldest queued slot (the one being consumed)
  std::size_t count_ = 0;             // queued slots, including the one being consumed
  bool stop_ = false;
  Pending pending_ = Pending::consume;  // what the worker does with queued frames once stop_
  std::exception_ptr error_;

  std::thread worker_;  // last: starts after everything above is initialised
};

}  // namespace fixstep
