#pragma once
// One extra thread that runs a job on demand while the caller does its own share (the planner splits the
// derivatives of an OCP and the assembly of its stage-wise KKT system over two cores). The thread lives as long as
// the object.
#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>

namespace centaur::common {

class WorkerThread {
 public:
  WorkerThread() : thread_([this] { loop(); }) {}
  ~WorkerThread() {
    {
      std::lock_guard<std::mutex> lock(m_);
      stop_ = true;
    }
    cv_.notify_all();
    thread_.join();
  }
  WorkerThread(const WorkerThread&) = delete;
  WorkerThread& operator=(const WorkerThread&) = delete;

  /// Start `job` on the worker (the previous one must have been waited for).
  void run(std::function<void()> job) {
    {
      std::lock_guard<std::mutex> lock(m_);
      job_ = std::move(job);
      pending_ = true;
    }
    cv_.notify_all();
  }
  /// Block until the job has finished.
  void wait() {
    std::unique_lock<std::mutex> lock(m_);
    cv_.wait(lock, [this] { return !pending_; });
  }

 private:
  void loop() {
    std::unique_lock<std::mutex> lock(m_);
    for (;;) {
      cv_.wait(lock, [this] { return stop_ || (pending_ && job_); });
      if (stop_) return;
      std::function<void()> job = std::move(job_);
      job_ = nullptr;
      lock.unlock();
      job();
      lock.lock();
      pending_ = false;
      cv_.notify_all();
    }
  }

  std::mutex m_;
  std::condition_variable cv_;
  std::function<void()> job_;
  bool pending_ = false, stop_ = false;
  std::thread thread_;
};

/// Runs `other` on `worker` while `mine` runs on the calling thread, and returns when both have finished; without a
/// worker, `mine` and then `other` on the calling thread.
inline void runAlongside(WorkerThread* worker, const std::function<void()>& mine, const std::function<void()>& other) {
  if (worker == nullptr) {
    mine();
    other();
    return;
  }
  worker->run(other);
  mine();
  worker->wait();
}

}  // namespace centaur::common
