// ctest-labels: unit
// common::ParallelChooser decides per kind of section whether the second thread runs. Fed with synthetic timings
// (wall time per unit of work, and the fraction of it the calling thread waited for the worker): fixed modes never
// switch; in auto mode a worker the caller never waits for keeps all the work, a worker that falls behind loses it
// after one trial of the other way, a change of the machine's state is noticed in either direction, and a single
// slow call switches nothing.
#include <gtest/gtest.h>

#include <functional>
#include <utility>
#include <vector>

#include "common/parallel_chooser.hpp"

using centaur::common::ParallelChooser;

namespace {

// Per call index and way: the wall time per unit and the caller's wait fraction.
using Cost = std::function<std::pair<double, double>(int, bool)>;

// `calls` calls of section 0; the way each ran.
std::vector<bool> runCalls(ParallelChooser& c, int calls, const Cost& cost) {
  std::vector<bool> way;
  for (int i = 0; i < calls; ++i) {
    const bool p = c.parallel(0);
    way.push_back(p);
    const auto [t, wait] = cost(i, p);
    c.record(0, p, t, wait);
  }
  return way;
}

int countParallel(const std::vector<bool>& way, int from, int to) {
  int n = 0;
  for (int i = from; i < to; ++i) n += way[i];
  return n;
}

ParallelChooser autoChooser() {
  ParallelChooser c;
  c.setMode(ParallelChooser::Mode::kAuto);
  return c;
}

}  // namespace

TEST(ParallelChooser, FixedModesNeverSwitch) {
  ParallelChooser par, in;
  in.setMode(ParallelChooser::Mode::kInline);
  EXPECT_EQ(par.mode(), ParallelChooser::Mode::kParallel);  // the default: both threads, as without a chooser
  const auto w = runCalls(par, 100, [](int, bool p) { return std::make_pair(p ? 5.0 : 1.0, 0.9); });
  EXPECT_EQ(countParallel(w, 0, 100), 100);
  const auto v = runCalls(in, 100, [](int, bool p) { return std::make_pair(p ? 1.0 : 5.0, 0.0); });
  EXPECT_EQ(countParallel(v, 0, 100), 0);
}

TEST(ParallelChooser, AWorkerTheCallerNeverWaitsForKeepsAllTheWork) {
  ParallelChooser c = autoChooser();
  // The caller alone would even be faster, but it never waited (< kWaitTrigger): nothing is tried.
  const auto w = runCalls(c, 200, [](int, bool p) { return std::make_pair(p ? 1.2 : 1.0, 0.02); });
  EXPECT_EQ(countParallel(w, 0, 200), 200);
}

TEST(ParallelChooser, AWorkerThatFallsBehindLosesTheWorkAfterOneTrial) {
  ParallelChooser c = autoChooser();
  // The caller waits half of each parallel call, and alone it is twice as fast: after the first two (parallel)
  // calls it tries inline, keeps it, and runs the second thread only to check every kExplore-th call.
  const int n = 200;
  const auto w = runCalls(c, n, [](int, bool p) { return std::make_pair(p ? 2.0 : 1.0, p ? 0.5 : 0.0); });
  EXPECT_TRUE(w[0] && w[1]);
  EXPECT_FALSE(w[2]);
  EXPECT_LE(countParallel(w, 3, n), n / ParallelChooser::kExplore + 1);
  EXPECT_GE(countParallel(w, 3, n), n / ParallelChooser::kExplore - 1);
  EXPECT_EQ(c.calls(0, true) + c.calls(0, false), n);
}

TEST(ParallelChooser, NoticesWhenTheMachineChangesEitherWay) {
  ParallelChooser c = autoChooser();
  // Calls 0-99 both threads fast; 100-199 the second thread falls behind (3x, the caller waiting 70 %); 200-299 it
  // is fast again.
  const auto w = runCalls(c, 300, [](int i, bool p) {
    if (!p) return std::make_pair(1.5, 0.0);
    return i >= 100 && i < 200 ? std::make_pair(4.5, 0.7) : std::make_pair(1.0, 0.01);
  });
  EXPECT_EQ(countParallel(w, 0, 100), 100);
  // From some call of the slow stretch on, the calling thread runs alone but for the trials (one in kExplore);
  // from some call after the recovery on, both threads run for good.
  int switched_in = -1, switched_back = -1;
  for (int i = 100; i < 200 && switched_in < 0; ++i)
    if (countParallel(w, i, i + ParallelChooser::kExplore - 1) == 0) switched_in = i;
  for (int i = 200; i < 300 && switched_back < 0; ++i)
    if (countParallel(w, i, 300) == 300 - i) switched_back = i;
  ASSERT_GE(switched_in, 0) << "the calling thread never took over while the second one was 3x slower";
  EXPECT_LE(switched_in - 100, ParallelChooser::kHistory + 2 * ParallelChooser::kExploreSlow);
  ASSERT_GE(switched_back, 0) << "the second thread never came back once it was fast again";
  EXPECT_LE(switched_back - 200, ParallelChooser::kExplore + 1);
}

TEST(ParallelChooser, OneSlowCallSwitchesNothing) {
  ParallelChooser c = autoChooser();
  // A preempted parallel call (10x, the caller waiting 90 % of it) among fast ones: the medians of the last
  // kHistory calls stay those of a worker that keeps up, so the calling thread alone is not even tried.
  const auto w = runCalls(c, 60, [](int i, bool p) {
    if (!p) return std::make_pair(1.4, 0.0);
    return i == 30 ? std::make_pair(10.0, 0.9) : std::make_pair(1.0, 0.02);
  });
  EXPECT_EQ(countParallel(w, 0, 60), 60);
}
