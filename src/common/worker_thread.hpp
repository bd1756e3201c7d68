#pragma once
// One extra thread that runs a job on demand while the caller does its own share (the planner splits the
// derivatives of an OCP and the assembly of its stage-wise KKT system over two cores). The thread lives as long as
// the object.
//
// Both sides poll before they block: the worker for its next job, the caller for the end of the job it waits for,
// each for up to `spin`. A thread blocked on a condition variable takes tens of microseconds to run again once
// woken, and the planner hands the worker three or four jobs per iteration of a few milliseconds. While polling,
// a thread uses its core (which the planner leaves idle between the jobs anyway).
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>

namespace centaur::common {

class WorkerThread {
 public:
  static constexpr std::chrono::microseconds kDefaultSpin{500};

  explicit WorkerThread(std::chrono::microseconds spin = kDefaultSpin) : spin_(spin), thread_([this] { loop(); }) {}
  ~WorkerThread() {
    {
      std::lock_guard<std::mutex> lock(m_);
      stop_.store(true, std::memory_order_relaxed);
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
      state_.store(kPending, std::memory_order_release);
    }
    cv_.notify_all();
  }
  /// Block until the job has finished (its effects are then visible to the caller).
  void wait() {
    if (poll([this] { return state_.load(std::memory_order_acquire) == kIdle; })) return;
    std::unique_lock<std::mutex> lock(m_);
    cv_.wait(lock, [this] { return state_.load(std::memory_order_acquire) == kIdle; });
  }

 private:
  enum State { kIdle, kPending, kRunning };

  // Poll `done` for up to spin_; true if it became true.
  template <class F>
  bool poll(const F& done) const {
    const auto until = std::chrono::steady_clock::now() + spin_;
    for (int i = 0;; ++i) {
      if (done()) return true;
      if ((i & 63) == 63) {
        if (std::chrono::steady_clock::now() >= until) return false;
        std::this_thread::yield();  // lets another thread of this core run, if any (a loaded machine)
      }
#if defined(__x86_64__) || defined(__i386__)
      __builtin_ia32_pause();
#else
      std::this_thread::yield();
#endif
    }
  }

  void loop() {
    auto has_work = [this] {
      return stop_.load(std::memory_order_relaxed) || state_.load(std::memory_order_acquire) == kPending;
    };
    for (;;) {
      poll(has_work);
      std::unique_lock<std::mutex> lock(m_);
      cv_.wait(lock, has_work);
      if (stop_.load(std::memory_order_relaxed)) return;
      std::function<void()> job = std::move(job_);
      job_ = nullptr;
      state_.store(kRunning, std::memory_order_relaxed);
      lock.unlock();
      job();
      lock.lock();
      state_.store(kIdle, std::memory_order_release);
      lock.unlock();
      cv_.notify_all();
    }
  }

  const std::chrono::microseconds spin_;
  std::mutex m_;
  std::condition_variable cv_;
  std::function<void()> job_;
  std::atomic<int> state_{kIdle};
  std::atomic<bool> stop_{false};
  std::thread thread_;  // last: started after the members it uses
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
