#include "sweep/dispatch.hpp"

#include <chrono>
#include <deque>

#include <nlohmann/json.hpp>

#include "common/error.hpp"

namespace centaur::sweep {

namespace {

using nlohmann::json;
using std::chrono::milliseconds;

/// Rank 0's book-keeping of one worker rank.
struct Worker {
  std::size_t outstanding = 0;  ///< runs handed out whose records did not come back yet
  bool told_no_more = false;    ///< a reply had fewer runs than asked for
  bool finished = false;
};

/// Handles every waiting message of the worker ranks: their records into `batch`, their requests from `queue`.
void serveRequests(const MpiSession& mpi, std::deque<std::size_t>& queue, std::vector<Worker>& workers,
                   int& active, std::vector<RunRecord>& batch) {
  int from = 0;
  while (mpi.poll(kTagToRoot, from)) {
    const json msg = json::parse(mpi.receive(from, kTagToRoot));
    Worker& w = workers.at(static_cast<std::size_t>(from));
    for (const json& r : msg.at("results")) {
      batch.push_back(recordFromJson(r, "a record from rank " + std::to_string(from)));
      --w.outstanding;
    }
    const std::size_t want = msg.at("want").get<std::size_t>();
    if (want > 0) {
      json runs = json::array();
      while (runs.size() < want && !queue.empty()) {
        runs.push_back(queue.front());
        queue.pop_front();
        ++w.outstanding;
      }
      if (runs.size() < want) w.told_no_more = true;
      mpi.send(from, kTagToWorker, json{{"runs", runs}}.dump());
    }
    if (w.told_no_more && w.outstanding == 0 && !w.finished) {
      w.finished = true;
      --active;
    }
  }
}

}  // namespace

void dispatchRuns(const std::vector<std::size_t>& todo, LocalPool& pool, const MpiSession* mpi,
                  const std::function<void(std::vector<RunRecord>&)>& sink) {
  std::deque<std::size_t> queue(todo.begin(), todo.end());
  std::vector<Worker> workers(mpi != nullptr ? static_cast<std::size_t>(mpi->size()) : 1);
  int active = mpi != nullptr ? mpi->size() - 1 : 0;
  const std::size_t local_depth = static_cast<std::size_t>(pool.threads()) + 1;
  std::size_t done = 0;
  std::vector<RunRecord> batch;
  while (done < todo.size() || active > 0) {
    while (!queue.empty() && pool.inFlight() < local_depth) {
      pool.push(queue.front());
      queue.pop_front();
    }
    if (mpi != nullptr) serveRequests(*mpi, queue, workers, active, batch);
    // Without workers to serve, sleep until a local run ends; with them, look at their messages every 2 ms.
    pool.take(batch, mpi != nullptr ? milliseconds(2) : milliseconds(1000));
    if (!batch.empty()) {
      done += batch.size();
      sink(batch);
      batch.clear();
    }
  }
}

void serveRuns(LocalPool& pool, const MpiSession& mpi) {
  bool more = true;
  std::size_t want = static_cast<std::size_t>(pool.threads()) + 1;
  std::vector<RunRecord> results;
  for (;;) {
    json out = json::array();
    for (const RunRecord& r : results) out.push_back(toJson(r));
    mpi.send(0, kTagToRoot, json{{"results", out}, {"want", more ? want : 0}}.dump());
    results.clear();
    if (more) {
      const json runs = json::parse(mpi.receive(0, kTagToWorker)).at("runs");
      for (const json& r : runs) pool.push(r.get<std::size_t>());
      more = runs.size() == want;
    }
    if (!more && pool.inFlight() == 0) return;
    while (!pool.take(results, milliseconds(100))) {
    }
    want = results.size();
  }
}

}  // namespace centaur::sweep
