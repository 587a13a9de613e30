// Box2d3Tasks: see discs_box2d3_tasks.hpp.
#include "discs_box2d3_tasks.hpp"

#include <algorithm>
#include <stdexcept>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace discs {

namespace {

void cpu_relax() {
#if defined(__x86_64__) || defined(__i386__)
  _mm_pause();
#else
  std::this_thread::yield();
#endif
}

/// Spins of an idle helper before it sleeps: some tens of microseconds, about the gaps between
/// Box2D's tasks within a step.
constexpr int idle_spins = 20'000;

}  // namespace

Box2d3Tasks::Box2d3Tasks(int workers) : workers_(workers) {
  if (workers < 2) throw std::invalid_argument("Box2d3Tasks: needs 2 or more workers");
  for (int k = 1; k < workers; ++k) threads_.emplace_back([this, k] { helper(std::uint32_t(k)); });
}

Box2d3Tasks::~Box2d3Tasks() {
  {
    const std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  for (std::thread& t : threads_) t.join();
}

void* Box2d3Tasks::enqueue(b2TaskCallback* task, int items, int min_range, void* task_context,
                           void* self) {
  auto& s = *static_cast<Box2d3Tasks*>(self);
  if (items <= 0) return nullptr;
  // Up to 4 pieces per worker, each of min_range items or more (the last takes the rest).
  const int pieces = std::clamp(items / std::max(min_range, 1), 1, 4 * s.workers_);
  Job& job = s.jobs_[s.next_job_++ % s.jobs_.size()];
  if (job.remaining.load(std::memory_order_acquire) != 0)
    throw std::logic_error("Box2d3Tasks: a task slot reused before its task finished");
  job.remaining.store(pieces, std::memory_order_relaxed);
  {
    const std::lock_guard lock(s.mutex_);
    for (int k = 0; k < pieces; ++k) {
      const int begin = int(std::int64_t(items) * k / pieces);
      const int end = int(std::int64_t(items) * (k + 1) / pieces);
      s.queue_.push_back({task, begin, end, task_context, &job});
    }
    s.queued_.fetch_add(pieces, std::memory_order_release);
  }
  s.wake_.notify_all();
  return &job;
}

void Box2d3Tasks::finish(void* user_task, void* self) {
  auto& s = *static_cast<Box2d3Tasks*>(self);
  const auto& job = *static_cast<const Job*>(user_task);
  Piece p;
  while (job.remaining.load(std::memory_order_acquire) > 0) {
    if (s.pop(p))
      run(p, 0);
    else
      cpu_relax();
  }
}

bool Box2d3Tasks::pop(Piece& p) {
  if (queued_.load(std::memory_order_acquire) == 0) return false;
  const std::lock_guard lock(mutex_);
  if (queue_.empty()) return false;
  p = queue_.front();
  queue_.pop_front();
  queued_.fetch_sub(1, std::memory_order_relaxed);
  return true;
}

void Box2d3Tasks::run(const Piece& p, std::uint32_t worker) {
  p.task(p.begin, p.end, worker, p.context);
  p.job->remaining.fetch_sub(1, std::memory_order_release);
}

void Box2d3Tasks::helper(std::uint32_t worker) {
  Piece p;
  for (;;) {
    int spins = 0;
    while (!pop(p)) {
      if (++spins < idle_spins) {
        cpu_relax();
        continue;
      }
      {
        std::unique_lock lock(mutex_);
        wake_.wait(lock, [this] { return stop_ || !queue_.empty(); });
        if (stop_) return;
      }
      spins = 0;
    }
    run(p, worker);
  }
}

}  // namespace discs
