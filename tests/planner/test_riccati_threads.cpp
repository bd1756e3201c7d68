// ctest-labels: unit
// The riccati backend's second thread is a choice of speed only. A whole interior-point solve of a (short) squat
// jump with the planner's worker in auto mode, with that worker slowed down by an injected delay before every job
// (a second core that falls behind), and with every section inline: the same iterations and the same iterate to
// the last bit; with the slow worker, the chooser leaves most of each kind of section to the calling thread.
#include <gtest/gtest.h>

#include <chrono>

#include "ocp_solver/interior_point.hpp"
#include "planner/jump_problem.hpp"
#include "planner/ocp_nlp.hpp"

using namespace centaur;
using namespace centaur::planner;
using Mode = common::ParallelChooser::Mode;

namespace {

struct SolveRun {
  ocp_solver::IpmResult result;
  int calls[4][2] = {};  // per kind of section: inline, parallel
};

SolveRun solve(const Ocp& ocp, Mode mode, std::chrono::microseconds delay) {
  OcpNlp nlp(ocp, true, nullptr, 2);
  nlp.worker()->chooser().setMode(mode);
  nlp.worker()->setJobDelay(delay);
  ocp_solver::StageKktSolver kkt(nlp.pattern(), nlp.stageLayout(), nlp.fixedVariables(), nlp.equalityRows());
  kkt.setPipelined(nlp.worker());
  SolveRun r;
  r.result = ocp_solver::solveInteriorPoint(nlp, kkt, ocp_solver::IpmOptions{});
  for (int s = 0; s < 4; ++s)
    for (int p = 0; p < 2; ++p) r.calls[s][p] = nlp.worker()->chooser().calls(s, p == 1);
  return r;
}

}  // namespace

TEST(RiccatiThreads, ASlowSecondCoreChangesTheSpeedNotTheSolve) {
  const JumpProblem p(loadJumpConfig("squat-jump", "", {"horizon.intervals=10", "horizon.takeoff=3",
                                                         "horizon.landing=7"}));
  using namespace std::chrono_literals;
  const SolveRun fast = solve(p.ocp(), Mode::kAuto, 0us), slow = solve(p.ocp(), Mode::kAuto, 3ms),
            alone = solve(p.ocp(), Mode::kInline, 0us);
  ASSERT_EQ(fast.result.status, ocp_solver::IpmStatus::kSolved);
  ASSERT_GT(fast.result.stats.iterations, 10);
  for (const SolveRun* r : {&slow, &alone}) {
    EXPECT_EQ(r->result.status, fast.result.status);
    EXPECT_EQ(r->result.stats.iterations, fast.result.stats.iterations);
    EXPECT_EQ(r->result.stats.factorizations, fast.result.stats.factorizations);
    EXPECT_EQ(r->result.x, fast.result.x);
    EXPECT_EQ(r->result.y, fast.result.y);
    EXPECT_EQ(r->result.objective, fast.result.objective);
  }
  // With a 3 ms delay per job the calling thread alone is far faster: after the warm-up and the first call, the
  // second thread only runs the trials of the other way (one in kExplore calls).
  for (int s : {common::kSectionDerivatives, common::kSectionFactor}) {
    const int in = slow.calls[s][0], par = slow.calls[s][1];
    EXPECT_GT(in, 3 * par) << "section " << s << ": " << in << " inline, " << par << " parallel";
  }
  for (int s = 0; s < 4; ++s) EXPECT_EQ(alone.calls[s][1], 0) << "section " << s;
}
