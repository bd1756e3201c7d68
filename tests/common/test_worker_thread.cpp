// ctest-labels: unit
// common::WorkerThread runs one job at a time beside the caller; both sides poll for up to `spin` before they block.
// Every job must run exactly once, in order, and its writes must be visible to the caller after wait(), whether
// either side found the other by polling or had to block and be woken.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>
#include <vector>

#include "common/worker_thread.hpp"

using centaur::common::runAlongside;
using centaur::common::WorkerThread;
using namespace std::chrono_literals;

namespace {

// Many short rounds: the worker fills one half of a buffer while the caller fills the other; after each round the
// caller reads both halves (plain, non-atomic data: wait() must order the worker's writes before the reads).
// Returns the first round in which an entry was not yet written or the job did not run exactly once (0: none).
int firstBadRound(WorkerThread& w, int rounds) {
  std::vector<long> data(256, 0);
  long ran = 0;
  for (int r = 1; r <= rounds; ++r) {
    runAlongside(
        &w, [&] { for (int i = 0; i < 128; ++i) data[i] = r * 1000 + i; },
        [&] {
          for (int i = 128; i < 256; ++i) data[i] = r * 1000 + i;
          ++ran;
        });
    for (int i = 0; i < 256; ++i)
      if (data[i] != r * 1000 + i) return r;
    if (ran != r) return r;
  }
  return 0;
}

}  // namespace

TEST(WorkerThread, PollingWorkerRunsEveryJobOnceAndItsWritesAreVisibleAfterWait) {
  WorkerThread w(10ms);  // both sides find each other by polling
  EXPECT_EQ(firstBadRound(w, 2000), 0);
}

TEST(WorkerThread, BlockingWorkerIsWokenForEveryJob) {
  WorkerThread w(0us);  // no polling: every job wakes the blocked worker, every wait blocks
  EXPECT_EQ(firstBadRound(w, 2000), 0);
}

TEST(WorkerThread, JobsAfterLongIdlePeriodsAndLongJobsStillComplete) {
  // The worker stops polling and blocks (idle longer than its spin); the caller blocks in wait() while a job runs
  // longer than the spin.
  WorkerThread w(200us);
  int ran = 0;
  for (int r = 0; r < 3; ++r) {
    std::this_thread::sleep_for(5ms);
    w.run([&] {
      std::this_thread::sleep_for(3ms);
      ++ran;
    });
    w.wait();
    EXPECT_EQ(ran, r + 1);
  }
}

TEST(WorkerThread, DestructionWhilePollingOrBlockedReturns) {
  { WorkerThread polling(1s); }  // destroyed while its worker polls for a first job
  {
    WorkerThread blocked(0us);
    std::this_thread::sleep_for(2ms);  // the worker is blocked on the condition variable
  }
  {
    WorkerThread after_job(1s);
    int x = 0;
    after_job.run([&] { x = 7; });
    after_job.wait();
    EXPECT_EQ(x, 7);
  }  // destroyed right after a job, its worker polling again
}

TEST(WorkerThread, InlineWorkerLeavesBothPartsToTheCallingThread) {
  WorkerThread w;
  const auto caller = std::this_thread::get_id();
  std::thread::id mine, other;
  w.setInline(true);
  runAlongside(&w, [&] { mine = std::this_thread::get_id(); }, [&] { other = std::this_thread::get_id(); });
  EXPECT_EQ(mine, caller);
  EXPECT_EQ(other, caller);
  w.setInline(false);
  runAlongside(&w, [&] { mine = std::this_thread::get_id(); }, [&] { other = std::this_thread::get_id(); });
  EXPECT_EQ(mine, caller);
  EXPECT_NE(other, caller);
}

TEST(WorkerThread, SectionsFollowTheChooserAndReportTheirTime) {
  // A worker that falls behind (a job delay of 2 ms, injected) beside a caller whose own part is short: in auto mode
  // the sections soon leave the work to the caller, who finishes each in far less than the delay.
  WorkerThread w;
  w.setJobDelay(2ms);
  w.chooser().setMode(centaur::common::ParallelChooser::Mode::kAuto);
  int other_ran = 0;
  for (int i = 0; i < 40; ++i) {
    const centaur::common::ParallelSection section(&w, centaur::common::kSectionDerivatives);
    runAlongside(&w, [] { std::this_thread::sleep_for(100us); }, [&] { ++other_ran; });
  }
  EXPECT_EQ(other_ran, 40);  // every job ran once, either way
  EXPECT_GE(w.chooser().calls(centaur::common::kSectionDerivatives, false), 30);
  EXPECT_LE(w.chooser().calls(centaur::common::kSectionDerivatives, true), 10);
}
