// ctest-labels: unit
// common::retainFreedMemory keeps freed memory in the process: a thread that repeatedly builds and frees
// workspaces of a few MB (as every planner solve does) faults its pages in once, not on every round.
// common::hugePagesForHeap puts the next allocations of the heap on 2 MiB pages: the first touch of ~16 MB of
// workspaces faults far fewer times. Each case runs in a child process, so that the allocator starts from its
// defaults.
#include <gtest/gtest.h>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "common/retain_memory.hpp"

namespace {

long minorFaults() {
  rusage r{};
  getrusage(RUSAGE_SELF, &r);
  return r.ru_minflt;
}

// Page faults of rounds 2..20 of building and freeing ~3 MB of vectors on a worker thread.
long faultsAfterTheFirstRound() {
  long faults = 0;
  std::thread worker([&] {
    for (int round = 0; round < 20; ++round) {
      const long f0 = minorFaults();
      {
        std::vector<std::vector<double>> blocks;
        for (int k = 0; k < 8; ++k) blocks.emplace_back(40000 + 1000 * k, 1.0);
      }
      { std::vector<double> big(600000, 2.0); }
      if (round > 0) faults += minorFaults() - f0;
    }
  });
  worker.join();
  return faults;
}

// Page faults of the first touch of ~16 MB of workspaces (what a fresh planner process fills), on this thread.
long faultsOfFirstTouch() {
  const long f0 = minorFaults();
  std::vector<std::vector<double>> blocks;
  for (int k = 0; k < 16; ++k) blocks.emplace_back(131072, 1.0);  // 1 MiB each
  return minorFaults() - f0;
}

// The value `measure` returns in a child process set up by `setup`; -1 if the child failed.
long inChild(const std::function<void()>& setup, const std::function<long()>& measure) {
  int fd[2];
  if (pipe(fd) != 0) return -1;
  const pid_t pid = fork();
  if (pid == 0) {
    setup();
    const long f = measure();
    const bool ok = write(fd[1], &f, sizeof f) == static_cast<ssize_t>(sizeof f);
    _exit(ok ? 0 : 1);
  }
  close(fd[1]);
  long f = -1;
  if (read(fd[0], &f, sizeof f) != static_cast<ssize_t>(sizeof f)) f = -1;
  close(fd[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) && WEXITSTATUS(status) == 0 ? f : -1;
}

// The system's transparent-huge-page mode: "always", "madvise", "never", or "" where the kernel has none.
std::string thpMode() {
  std::ifstream f("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  std::getline(f, line);
  const auto a = line.find('['), b = line.find(']');
  return a == std::string::npos || b == std::string::npos ? "" : line.substr(a + 1, b - a - 1);
}

long faultsInChild(bool retain) {
  return inChild([retain] { if (retain) centaur::common::retainFreedMemory(); }, faultsAfterTheFirstRound);
}

}  // namespace

TEST(RetainMemory, RepeatedWorkspacesFaultInOnce) {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  GTEST_SKIP() << "the sanitizers bring their own allocator";
#endif
  const long kept = faultsInChild(true), returned = faultsInChild(false);
  ASSERT_GE(kept, 0);
  ASSERT_GE(returned, 0);
  // ~3 MB per round = ~750 pages: glibc's defaults fault most of them in again every round (19 rounds).
  EXPECT_LT(kept, 50) << "with retainFreedMemory";
  EXPECT_GT(returned, 500) << "glibc's defaults (the reason for retainFreedMemory)";
}

TEST(RetainMemory, HugePagesForTheHeapFaultItsWorkspacesInFarFewerTimes) {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  GTEST_SKIP() << "the sanitizers bring their own allocator";
#endif
  const std::string mode = thpMode();
  if (mode != "madvise" && mode != "always") GTEST_SKIP() << "transparent huge pages are off here (" << mode << ")";
  using centaur::common::hugePagesForHeap;
  using centaur::common::retainFreedMemory;
  const long huge = inChild(retainFreedMemory, [] { return hugePagesForHeap(24 << 20) ? faultsOfFirstTouch() : -2; });
  const long small = inChild(retainFreedMemory, faultsOfFirstTouch);
  ASSERT_NE(huge, -2) << "the kernel refused the advice";
  ASSERT_GE(huge, 0);
  ASSERT_GE(small, 0);
  // 16 MiB in 4 KiB pages is ~4 100 faults; on 2 MiB pages, a few, plus the 4 KiB pages before the first boundary.
  EXPECT_LT(huge, 1000) << "with hugePagesForHeap";
  if (mode == "madvise") {
    EXPECT_GT(small, 3000) << "without (the system's mode is madvise)";
  }
}
