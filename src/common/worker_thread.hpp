#pragma once
// One extra thread that runs a job on demand while the caller does its own share (the planner splits the
// derivatives of an OCP and the assembly of its stage-wise KKT system over two cores). The thread lives as long as
// the object.
//
// Both sides poll before they block: the worker for its next job, the caller for the end of the job it waits for,
// each for up to `spin`. A thread blocked on a condition variable takes tens of microseconds to run again once
// woken, and the planner hands the worker three or four jobs per iteration of a few milliseconds. While polling,
// a thread uses its core (which the planner leaves idle between the jobs anyway).
//
// Inline mode: the callers run the jobs themselves (runAlongside, and the users that check isInline()); the thread
// then sleeps. A ParallelSection sets it per section as the worker's ParallelChooser decides.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>

#include "common/parallel_chooser.hpp"

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
  /// Inline: runAlongside runs both parts on the calling thread, and users of run() check isInline() first. Only
  /// between jobs, by the thread that hands them over.
  void setInline(bool on) { inline_ = on; }
  bool isInline() const { return inline_; }
  /// Which sections run inline (ParallelSection); its mode is kParallel unless the owner sets another.
  ParallelChooser& chooser() { return chooser_; }
  /// Fault injection for tests: the thread sleeps this long before each job (a second core that falls behind).
  void setJobDelay(std::chrono::microseconds d) { delay_ = d; }

  /// Block until the job has finished (its effects are then visible to the caller).
  void wait() {
    const auto idle = [this] { return state_.load(std::memory_order_acquire) == kIdle; };
    if (idle()) return;
    const auto t0 = std::chrono::steady_clock::now();
    if (!poll(idle)) {
      std::unique_lock<std::mutex> lock(m_);
      cv_.wait(lock, idle);
    }
    addWaited(std::chrono::steady_clock::now() - t0);
  }
  /// The calling side's time spent waiting for the worker, in wait() and wherever a user of run() adds its own
  /// waits (addWaited); ParallelSection compares it with the section's time.
  void addWaited(std::chrono::steady_clock::duration d) { waited_ += std::chrono::duration<double>(d).count(); }
  double waited() const { return waited_; }

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
      if (delay_.count() > 0) std::this_thread::sleep_for(delay_);
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
  bool inline_ = false;
  double waited_ = 0.0;  // [s] the calling side's waits
  ParallelChooser chooser_;
  std::chrono::microseconds delay_{0};  // read by the thread only after a job was handed over under the mutex
  std::thread thread_;  // last: started after the members it uses
};

/// One call of a kind of section (ParallelChooser) on `worker` (may be null): decides whether it runs inline, and
/// records its wall time per unit of work (setWork; 1 unless set, 0 to leave it out) and the fraction of it the
/// caller spent waiting for the worker when it ends.
class ParallelSection {
 public:
  ParallelSection(WorkerThread* worker, int section) : worker_(worker), section_(section) {
    if (!worker_) return;
    parallel_ = worker_->chooser().parallel(section_);
    worker_->setInline(!parallel_);
    waited0_ = worker_->waited();
    t0_ = std::chrono::steady_clock::now();
  }
  ~ParallelSection() {
    if (!worker_ || work_ <= 0.0) return;
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
    const double waited = worker_->waited() - waited0_;
    worker_->chooser().record(section_, parallel_, s / work_, s > 0.0 ? waited / s : 0.0);
  }
  ParallelSection(const ParallelSection&) = delete;
  ParallelSection& operator=(const ParallelSection&) = delete;
  void setWork(double units) { work_ = units; }

 private:
  WorkerThread* worker_;
  int section_;
  bool parallel_ = true;
  double work_ = 1.0;
  double waited0_ = 0.0;
  std::chrono::steady_clock::time_point t0_;
};

/// Runs `other` on `worker` while `mine` runs on the calling thread, and returns when both have finished; without a
/// worker, `mine` and then `other` on the calling thread.
inline void runAlongside(WorkerThread* worker, const std::function<void()>& mine, const std::function<void()>& other) {
  if (worker == nullptr || worker->isInline()) {
    mine();
    other();
    return;
  }
  worker->run(other);
  mine();
  worker->wait();
}

}  // namespace centaur::common
