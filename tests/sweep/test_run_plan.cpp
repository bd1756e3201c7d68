// ctest-labels: unit sweep
// The runs of a sweep: index <-> (point, seed, mode); seeds shared by the modes of a sample (paired comparisons),
// different across samples and points, and the same for the same parameters in another grid; samples inside their
// distributions with the right moments; a key's samples do not depend on the other keys; Wilson intervals.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "sweep/run_plan.hpp"
#include "sweep/summary.hpp"

using namespace centaur::sweep;

namespace {

SweepSpec spec(const std::string& axes, const std::string& perturb, int seeds = 5) {
  return parseSweepSpec("jumps: [squat-jump]\nmodes: [none, raibert, ocp]\nseeds: " + std::to_string(seeds) +
                            "\nplanner: {axes: {" + axes + "}}\nsimulation: {perturb: {" + perturb + "}}\n",
                        "spec.yaml");
}

}  // namespace

TEST(RunPlan, IndexSeedsAndPairing) {
  const SweepSpec s = spec("target.height: [0.85, 0.87], contact.mu: [0.5, 0.6]", "world.friction: {uniform: [0.5, 1]}");
  std::set<std::uint64_t> seeds;
  for (std::size_t run = 0; run < s.runs(); ++run) {
    const RunId id = runId(s, run);
    EXPECT_EQ((id.point * 5 + id.seed_index) * 3 + id.mode, run);
    const std::uint64_t seed = runSeed(s, id.point, id.seed_index);
    if (id.mode == 0) {
      EXPECT_TRUE(seeds.insert(seed).second) << "seed reused by run " << run;
    }
    EXPECT_EQ(runOverrides(s, id.point, id.seed_index), runOverrides(s, id.point, id.seed_index));
  }
  EXPECT_EQ(seeds.size(), 4u * 5u);
  // The same parameters in a larger grid: the same seed and sample (point 1 of s = 0.85/0.6).
  const SweepSpec t = spec("target.height: [0.85, 0.86, 0.87], contact.mu: [0.5, 0.6]", "world.friction: {uniform: [0.5, 1]}");
  EXPECT_EQ(runSeed(s, 1, 3), runSeed(t, 1, 3));
  EXPECT_EQ(runOverrides(s, 1, 3), runOverrides(t, 1, 3));
  EXPECT_NE(runSeed(s, 2, 3), runSeed(t, 2, 3));  // 0.87/0.5 vs 0.86/0.5
}

TEST(RunPlan, SamplesFollowTheirDistributions) {
  const SweepSpec s = spec("target.height: [0.85]",
                           "world.friction: {uniform: [0.5, 1]}, robot.mass_scale: {normal: [1, 0.05], clip: [0.9, 1.1]}, "
                           "sensors.latency_periods: {uniform: [0, 2]}, push.impulse: {choice: [0, 10]}",
                           4000);
  double sum = 0.0, sum2 = 0.0;
  int latency[3] = {0, 0, 0}, pushes = 0;
  for (int k = 0; k < 4000; ++k) {
    const auto v = samplePerturbation(s, runSeed(s, 0, static_cast<std::size_t>(k)));
    // order: push.impulse, robot.mass_scale, sensors.latency_periods, world.friction
    EXPECT_TRUE(v[0][0] == 0.0 || v[0][0] == 10.0);
    pushes += v[0][0] == 10.0;
    EXPECT_GE(v[1][0], 0.9);
    EXPECT_LE(v[1][0], 1.1);
    sum += v[1][0];
    sum2 += v[1][0] * v[1][0];
    ASSERT_TRUE(v[2][0] == 0.0 || v[2][0] == 1.0 || v[2][0] == 2.0) << v[2][0];
    ++latency[static_cast<int>(v[2][0])];
    EXPECT_GE(v[3][0], 0.5);
    EXPECT_LT(v[3][0], 1.0);
  }
  const double mean = sum / 4000, sd = std::sqrt(sum2 / 4000 - mean * mean);
  EXPECT_NEAR(mean, 1.0, 0.004);  // 4.5 standard errors of the mean
  EXPECT_NEAR(sd, 0.05, 0.003);   // clipping at 2 sigma takes ~12 % off the standard deviation at most
  for (int l : latency) EXPECT_NEAR(l / 4000.0, 1.0 / 3.0, 0.035);
  EXPECT_NEAR(pushes / 4000.0, 0.5, 0.035);
  // Adding a key leaves the samples of the others as they were.
  const SweepSpec fewer = spec("target.height: [0.85]", "world.friction: {uniform: [0.5, 1]}", 4000);
  EXPECT_EQ(samplePerturbation(fewer, runSeed(fewer, 0, 7))[0], samplePerturbation(s, runSeed(s, 0, 7))[3]);
}

TEST(Summary, WilsonInterval) {
  // Reference values of the Wilson score interval (z = 1.96).
  const Interval a = wilson(0, 10), b = wilson(5, 10), c = wilson(10, 10), d = wilson(81, 100);
  EXPECT_NEAR(a.lo, 0.0, 1e-12);
  EXPECT_NEAR(a.hi, 0.2775, 1e-4);
  EXPECT_NEAR(b.lo, 0.2366, 1e-4);
  EXPECT_NEAR(b.hi, 0.7634, 1e-4);
  EXPECT_NEAR(c.lo, 0.7225, 1e-4);
  EXPECT_NEAR(c.hi, 1.0, 1e-12);
  EXPECT_NEAR(d.lo, 0.7222, 1e-4);
  EXPECT_NEAR(d.hi, 0.8749, 1e-4);
}
