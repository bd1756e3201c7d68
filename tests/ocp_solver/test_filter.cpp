// ctest-labels: unit
// The line search's filter (filter.hpp): dominance, and Ipopt's filter reset heuristic, which empties the filter
// when the last rejection before an accepted trial was the filter's in 5 accepted steps in a row, at most 5 times
// per solve, and whose count starts over with every new barrier problem.
#include <gtest/gtest.h>

#include "ocp_solver/filter.hpp"

using centaur::ocp_solver::Filter;

namespace {

// A filter with one entry, (theta, phi) = (1, 1), that blocks the trial point (2, 2).
Filter filterWithOneEntry() {
  Filter f;
  f.start(100.0);
  f.add(1.0, 1.0);
  return f;
}

// An iteration whose line search is first blocked by the filter and then accepts a shorter step.
bool blockedThenAccepted(Filter& f) {
  EXPECT_FALSE(f.acceptable(2.0, 2.0));
  f.rejectedByFilter();
  return f.accepted();
}

}  // namespace

TEST(Filter, DominatedPointsAndPointsAboveThetaMaxAreRejected) {
  Filter f = filterWithOneEntry();
  EXPECT_FALSE(f.acceptable(1.0, 1.0));
  EXPECT_FALSE(f.acceptable(2.0, 1.5));
  EXPECT_TRUE(f.acceptable(0.5, 2.0));
  EXPECT_TRUE(f.acceptable(2.0, 0.5));
  EXPECT_FALSE(f.acceptable(101.0, 0.0));
  f.add(0.5, 0.5);  // dominates (1, 1), which goes
  EXPECT_EQ(f.size(), 1u);
}

TEST(Filter, EmptiedAfterFiveAcceptedStepsThatTheFilterHadBlocked) {
  Filter f = filterWithOneEntry();
  for (int i = 0; i < Filter::kResetTrigger - 1; ++i) {
    EXPECT_FALSE(blockedThenAccepted(f)) << i;
    EXPECT_EQ(f.size(), 1u);
  }
  EXPECT_TRUE(blockedThenAccepted(f));
  EXPECT_EQ(f.size(), 0u);
  EXPECT_TRUE(f.acceptable(2.0, 2.0));
  EXPECT_EQ(f.heuristicResets(), 1);
  EXPECT_EQ(f.thetaMax(), 100.0);  // only the entries go
}

TEST(Filter, AnotherLastRejectionOrNoneStartsTheCountOver) {
  Filter f = filterWithOneEntry();
  for (int i = 0; i < Filter::kResetTrigger - 1; ++i) blockedThenAccepted(f);
  // The last rejection before this accepted step was the test against the current point, not the filter.
  f.rejectedByFilter();
  f.rejectedByCurrentPoint();
  EXPECT_FALSE(f.accepted());
  for (int i = 0; i < Filter::kResetTrigger - 1; ++i) EXPECT_FALSE(blockedThenAccepted(f)) << i;
  EXPECT_FALSE(f.accepted());  // a full step, nothing rejected before it
  for (int i = 0; i < Filter::kResetTrigger - 1; ++i) EXPECT_FALSE(blockedThenAccepted(f)) << i;
  EXPECT_EQ(f.size(), 1u);
  EXPECT_TRUE(blockedThenAccepted(f));
}

TEST(Filter, ANewBarrierProblemStartsTheCountOver) {
  Filter f = filterWithOneEntry();
  for (int i = 0; i < Filter::kResetTrigger - 1; ++i) blockedThenAccepted(f);
  f.reset(100.0);
  f.add(1.0, 1.0);
  for (int i = 0; i < Filter::kResetTrigger - 1; ++i) EXPECT_FALSE(blockedThenAccepted(f)) << i;
  EXPECT_TRUE(blockedThenAccepted(f));
}

TEST(Filter, AtMostFiveResetsPerSolve) {
  Filter f = filterWithOneEntry();
  for (int r = 0; r < Filter::kMaxResets + 2; ++r) {
    f.add(1.0, 1.0);
    for (int i = 0; i < Filter::kResetTrigger; ++i) blockedThenAccepted(f);
    EXPECT_EQ(f.size(), r < Filter::kMaxResets ? 0u : 1u) << "round " << r;
  }
  EXPECT_EQ(f.heuristicResets(), Filter::kMaxResets);
  f.start(100.0);  // the next solve has its budget again
  f.add(1.0, 1.0);
  for (int i = 0; i < Filter::kResetTrigger; ++i) blockedThenAccepted(f);
  EXPECT_EQ(f.size(), 0u);
}
