#include "sweep/local_pool.hpp"

#include <algorithm>

namespace centaur::sweep {

LocalPool::LocalPool(int threads, std::function<RunRecord(std::size_t)> work) : work_(std::move(work)) {
  for (int i = 0; i < std::max(threads, 1); ++i) threads_.emplace_back([this] { loop(); });
}

LocalPool::~LocalPool() {
  {
    std::lock_guard<std::mutex> lock(m_);
    closing_ = true;
  }
  task_cv_.notify_all();
  for (auto& t : threads_) t.join();
}

void LocalPool::push(std::size_t task) {
  {
    std::lock_guard<std::mutex> lock(m_);
    tasks_.push_back(task);
    ++in_flight_;
  }
  task_cv_.notify_one();
}

std::size_t LocalPool::inFlight() const {
  std::lock_guard<std::mutex> lock(m_);
  return in_flight_;
}

bool LocalPool::take(std::vector<RunRecord>& out, std::chrono::milliseconds timeout) {
  std::unique_lock<std::mutex> lock(m_);
  if (done_.empty()) done_cv_.wait_for(lock, timeout, [this] { return !done_.empty(); });
  if (done_.empty()) return false;
  in_flight_ -= done_.size();
  for (auto& r : done_) out.push_back(std::move(r));
  done_.clear();
  return true;
}

void LocalPool::loop() {
  for (;;) {
    std::size_t task = 0;
    {
      std::unique_lock<std::mutex> lock(m_);
      task_cv_.wait(lock, [this] { return closing_ || !tasks_.empty(); });
      if (tasks_.empty()) return;  // closing and nothing left
      task = tasks_.front();
      tasks_.pop_front();
    }
    RunRecord r = work_(task);
    {
      std::lock_guard<std::mutex> lock(m_);
      done_.push_back(std::move(r));
    }
    done_cv_.notify_one();
  }
}

}  // namespace centaur::sweep
