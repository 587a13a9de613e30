// A small task system for Box2D v3's b2WorldDef::enqueueTask / finishTask (bench_discs only):
// `workers` - 1 helper threads plus the thread that calls b2World_Step, which is worker 0.
//
// Box2D v3 hands its task system parallel-for ranges (b2TaskCallback over [0, itemCount), at
// least minRange items a piece) and, in its solver, one task per worker that spins on the
// solver's stages, so the tasks of one step must be able to run at the same time (Box2D's
// types.h, "Task interface"; its samples use enkiTS, whose threads spin a while before they
// sleep). Here: a queue of pieces under a mutex; a helper thread takes pieces, spins on the
// queue for a while when it is empty, then sleeps on a condition variable; finish() runs queued
// pieces on the calling thread until the task's pieces are done. A worker index is a thread's
// own (the caller 0, helper k k), and a thread runs one piece at a time, so no index is in use
// twice at once, as Box2D requires.
#pragma once

#include <box2d/box2d.h>

#include <array>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <thread>
#include <vector>

namespace discs {

class Box2d3Tasks {
 public:
  /// `workers` >= 2: the caller and `workers` - 1 helper threads.
  explicit Box2d3Tasks(int workers);
  ~Box2d3Tasks();
  Box2d3Tasks(const Box2d3Tasks&) = delete;
  Box2d3Tasks& operator=(const Box2d3Tasks&) = delete;

  [[nodiscard]] int workers() const { return workers_; }
  /// b2EnqueueTaskCallback (userContext: this).
  static void* enqueue(b2TaskCallback* task, int items, int min_range, void* task_context,
                       void* self);
  /// b2FinishTaskCallback (userContext: this).
  static void finish(void* user_task, void* self);

 private:
  struct Job {
    std::atomic<int> remaining{0};  ///< pieces not yet run to their end
  };
  struct Piece {
    b2TaskCallback* task = nullptr;
    int begin = 0, end = 0;
    void* context = nullptr;
    Job* job = nullptr;
  };
  bool pop(Piece& p);
  static void run(const Piece& p, std::uint32_t worker);
  void helper(std::uint32_t worker);

  int workers_ = 1;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<Piece> queue_;
  std::atomic<int> queued_{0};
  bool stop_ = false;
  // Jobs of one step are few (Box2D enqueues about ten a step) and all finished within it; a
  // slot is reused only after 256 others, and only when its job is done (checked).
  std::array<Job, 256> jobs_{};
  std::size_t next_job_ = 0;
  std::vector<std::thread> threads_;
};

}  // namespace discs
