// The task system Box3D's world runs its parallel loops on
// (box3d_runner.cpp): the enqueue/finish pair of b3WorldDef (Box3D's
// types.h, b3EnqueueTaskCallback and b3FinishTaskCallback) over
// `threads - 1` std::threads, the stepping thread being the last one.
//
// Finish blocks until its task is done; a task no helper has started yet is
// run there by the caller instead of waited for, so the caller works too and
// a step never waits on a queue (Box3D's own scheduler helps the same way
// while it waits). A task is taken by exactly one thread: a helper pops it
// from the queue, or Finish takes it out of the queue.
#pragma once

#include <algorithm>
#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace contactsim::bench {

class Box3dTaskPool {
 public:
  using TaskFn = void(void* task_context);

  explicit Box3dTaskPool(int threads) {
    for (int i = 1; i < threads; ++i) helpers_.emplace_back([this] { HelperLoop(); });
  }
  ~Box3dTaskPool() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stopping_ = true;
    }
    work_.notify_all();
    for (std::thread& t : helpers_) t.join();
  }
  Box3dTaskPool(const Box3dTaskPool&) = delete;
  Box3dTaskPool& operator=(const Box3dTaskPool&) = delete;

  // b3EnqueueTaskCallback: the returned handle goes to Finish exactly once.
  static void* Enqueue(TaskFn* fn, void* task_context, void* pool, const char* /*name*/) {
    return static_cast<Box3dTaskPool*>(pool)->Push(fn, task_context);
  }
  // b3FinishTaskCallback: returns when the task has run.
  static void Finish(void* task, void* pool) { static_cast<Box3dTaskPool*>(pool)->Wait(static_cast<Task*>(task)); }

 private:
  struct Task {
    TaskFn* fn;
    void* context;
    bool done = false;  // guarded by mutex_
  };

  Task* Push(TaskFn* fn, void* context) {
    auto* task = new Task{fn, context};
    {
      std::lock_guard<std::mutex> lock(mutex_);
      queue_.push_back(task);
    }
    work_.notify_one();
    return task;
  }

  void Wait(Task* task) {
    std::unique_lock<std::mutex> lock(mutex_);
    const auto queued = std::find(queue_.begin(), queue_.end(), task);
    if (queued != queue_.end()) {
      // not started: the caller runs it
      queue_.erase(queued);
      lock.unlock();
      task->fn(task->context);
    } else {
      done_.wait(lock, [task] { return task->done; });
    }
    delete task;  // a helper sets `done` last and under the lock: no one touches it any more
  }

  void HelperLoop() {
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      work_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
      if (queue_.empty()) return;  // stopping, nothing left
      Task* task = queue_.front();
      queue_.pop_front();
      lock.unlock();
      task->fn(task->context);
      lock.lock();
      task->done = true;
      done_.notify_all();
    }
  }

  std::mutex mutex_;
  std::condition_variable work_;  // a task was queued, or the pool stops
  std::condition_variable done_;  // a helper finished a task
  std::deque<Task*> queue_;
  bool stopping_ = false;
  std::vector<std::thread> helpers_;
};

}  // namespace contactsim::bench
