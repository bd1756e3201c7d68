#pragma once
// A process's simulation threads: tasks (run indices) go in with push(), records come out on the thread that
// owns the pool (take()), which is the only one that writes files or talks MPI. Each worker thread runs one
// task at a time through `work` (it must not throw; executeRun never does).
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include "sweep/run_record.hpp"

namespace centaur::sweep {

class LocalPool {
 public:
  LocalPool(int threads, std::function<RunRecord(std::size_t)> work);
  /// Joins the threads after the queued tasks are done.
  ~LocalPool();
  LocalPool(const LocalPool&) = delete;
  LocalPool& operator=(const LocalPool&) = delete;

  int threads() const { return static_cast<int>(threads_.size()); }
  void push(std::size_t task);
  /// Tasks queued or running whose records were not taken yet.
  std::size_t inFlight() const;
  /// Moves the finished records into `out`, waiting up to `timeout` for at least one; false if none came.
  bool take(std::vector<RunRecord>& out, std::chrono::milliseconds timeout);

 private:
  void loop();

  std::function<RunRecord(std::size_t)> work_;
  mutable std::mutex m_;
  std::condition_variable task_cv_, done_cv_;
  std::deque<std::size_t> tasks_;
  std::vector<RunRecord> done_;
  std::size_t in_flight_ = 0;
  bool closing_ = false;
  std::vector<std::thread> threads_;
};

}  // namespace centaur::sweep
