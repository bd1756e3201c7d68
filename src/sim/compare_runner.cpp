#include "sim/compare_runner.hpp"

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <set>
#include <thread>

#include "common/error.hpp"
#include "sim/scenario.hpp"

namespace centaur::sim {

namespace {

BatchResult runOne(const BatchRun& run) {
  BatchResult r;
  const auto t0 = std::chrono::steady_clock::now();
  try {
    const Scenario* scenario = findScenario(run.scenario);
    if (scenario == nullptr) {
      std::string names;
      for (const auto& s : scenarios()) names += (names.empty() ? "" : ", ") + s.name;
      throw InputError("unknown scenario '" + run.scenario + "' (registered: " + names + ")");
    }
    r.summary = runScenario(*scenario, run.config_file, run.overrides, run.options, run.outputs);
    r.status = BatchResult::Status::Completed;
  } catch (const InputError& e) {
    r.status = BatchResult::Status::BadInput;
    r.error = e.what();
  } catch (const std::exception& e) {
    r.status = BatchResult::Status::RuntimeFailure;
    r.error = e.what();
  } catch (...) {
    r.status = BatchResult::Status::RuntimeFailure;
    r.error = "unknown exception";
  }
  r.elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace

int batchThreads(int jobs, std::size_t runs) {
  int n = jobs > 0 ? jobs : static_cast<int>(std::thread::hardware_concurrency());
  n = std::max(n, 1);
  return static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(n), std::max<std::size_t>(runs, 1)));
}

std::vector<BatchResult> runBatch(const std::vector<BatchRun>& runs, int jobs, const BatchCallbacks& callbacks) {
  std::vector<BatchResult> results(runs.size());
  std::mutex m;  // guards taken, busy, done and the callbacks
  std::condition_variable cv;
  std::vector<bool> taken(runs.size(), false);
  std::set<std::string> busy;  // exclusive groups currently running
  std::size_t done = 0;

  auto worker = [&]() {
    for (;;) {
      std::size_t index = runs.size();
      {
        std::unique_lock<std::mutex> lock(m);
        for (;;) {
          bool untaken = false;
          for (std::size_t i = 0; i < runs.size(); ++i) {
            if (taken[i]) continue;
            untaken = true;
            const std::string& g = runs[i].exclusive_group;
            if (g.empty() || busy.count(g) == 0) {
              index = i;
              break;
            }
          }
          if (index < runs.size() || !untaken) break;
          cv.wait(lock);  // every remaining run waits for a busy group
        }
        if (index == runs.size()) return;
        taken[index] = true;
        if (!runs[index].exclusive_group.empty()) busy.insert(runs[index].exclusive_group);
        if (callbacks.started) callbacks.started(index);
      }
      BatchResult r = runOne(runs[index]);
      {
        std::lock_guard<std::mutex> lock(m);
        results[index] = std::move(r);
        if (!runs[index].exclusive_group.empty()) busy.erase(runs[index].exclusive_group);
        ++done;
        if (callbacks.finished) callbacks.finished(index, results[index], done, runs.size());
      }
      cv.notify_all();
    }
  };

  const int threads = batchThreads(jobs, runs.size());
  if (threads <= 1) {
    worker();
  } else {
    std::vector<std::thread> pool;
    pool.reserve(static_cast<std::size_t>(threads));
    for (int i = 0; i < threads; ++i) pool.emplace_back(worker);
    for (auto& t : pool) t.join();
  }
  return results;
}

}  // namespace centaur::sim
