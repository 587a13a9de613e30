// FramePipeline: the producer/worker ring of frame buffers (see frame_pipeline.hpp).
#include "fixstep/capture/frame_pipeline.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace fixstep {

FramePipeline::FramePipeline(std::size_t frame_bytes, std::size_t slots, Consumer consume,
                             Pending at_destruction)
    : frame_bytes_(frame_bytes), consume_(std::move(consume)), at_destruction_(at_destruction) {
  if (frame_bytes == 0 || slots == 0) {
    throw std::invalid_argument(fmt::format(
        "FramePipeline: {} slots of {} bytes; both must be at least 1", slots, frame_bytes));
  }
  slots_.assign(slots, std::vector<std::uint8_t>(frame_bytes));
  tags_.assign(slots, 0);
  worker_ = std::thread([this] { work(); });
}

FramePipeline::~FramePipeline() {
  try {
    stop(at_destruction_);
  } catch (...) {  // NOLINT(bugprone-empty-catch): the error was the caller's to fetch
  }
}

std::exception_ptr FramePipeline::error() const {
  const std::lock_guard lock(mutex_);
  return error_;
}

void FramePipeline::submit(std::span<const std::uint8_t> frame, std::uint64_t tag) {
  if (frame.size() != frame_bytes_) {
    throw std::invalid_argument(
        fmt::format("FramePipeline: a frame of {} bytes, expected {}", frame.size(), frame_bytes_));
  }
  if (!running()) {
    if (error_) std::rethrow_exception(error_);
    throw std::logic_error("FramePipeline: submit() after stop()");
  }
  std::size_t slot = 0;
  {
    std::unique_lock lock(mutex_);
    released_.wait(lock, [&] { return count_ < slots_.size() || error_; });
    if (error_) std::rethrow_exception(error_);
    slot = (head_ + count_) % slots_.size();
  }
  // The slot is outside [head_, head_ + count_): the worker does not touch it until count_
  // grows below, and only this (the one producer) thread changes what lies past count_.
  std::copy(frame.begin(), frame.end(), slots_[slot].begin());
  tags_[slot] = tag;
  {
    const std::lock_guard lock(mutex_);
    ++count_;
  }
  queued_.notify_one();
}

void FramePipeline::drain() {
  std::unique_lock lock(mutex_);
  released_.wait(lock, [&] { return count_ == 0 || error_; });
  if (error_) std::rethrow_exception(error_);
}

void FramePipeline::stop(Pending pending) {
  if (running()) {
    {
      const std::lock_guard lock(mutex_);
      stop_ = true;
      pending_ = pending;
    }
    queued_.notify_one();
    worker_.join();
  }
  if (error_) std::rethrow_exception(error_);
}

void FramePipeline::work() {
  std::unique_lock lock(mutex_);
  for (;;) {
    queued_.wait(lock, [&] { return count_ > 0 || stop_; });
    if (stop_ && (count_ == 0 || pending_ == Pending::drop)) return;
    const std::size_t slot = head_;
    lock.unlock();
    std::exception_ptr error;
    try {
      consume_(slots_[slot], tags_[slot]);
    } catch (...) {
      error = std::current_exception();
    }
    lock.lock();
    if (error) {  // stop: the frames queued after the failed one are never consumed
      error_ = error;
      released_.notify_all();
      return;
    }
    head_ = (head_ + 1) % slots_.size();
    --count_;
    released_.notify_all();
  }
}

}  // namespace fixstep
