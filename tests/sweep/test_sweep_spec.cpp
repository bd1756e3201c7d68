// ctest-labels: unit sweep
// The sweep spec: ranges and lists expand to the documented grid, the canonical text is a fixed point (what an
// MPI rank parses again and what a resumed DIR is compared with), and every bad spec of the issue's list (unknown
// key, empty axis, reversed range, unknown mode, negative seeds, a planner key that does not exist) and a few more
// are InputError naming the spec file and the key.
#include <gtest/gtest.h>

#include <string>

#include "common/error.hpp"
#include "sweep/sweep_spec.hpp"

using namespace centaur;
using namespace centaur::sweep;

namespace {

const char* kSpec = R"(jumps: [half-squat-jump]
modes: [none, raibert]
seeds: 4
seed: 11
planner:
  set: {solver.max_iter: 400}
  axes:
    target.wall_distance: {from: 0.1, to: 0.2, steps: 3}
    target.wall_height: [0.15, 0.2]
simulation:
  set:
    duration: 1.0
    sensors.noise.q: 0.001
  perturb:
    world.friction: {uniform: [0.5, 1.0]}
    robot.com_offset: {uniform: [[-0.02, -0.02, 0], [0.02, 0.02, 0]]}
    sensors.latency_periods: {choice: [0, 1]}
    push.impulse: {normal: [5, 2], clip: [0, 10]}
)";

std::string message(const std::string& text) {
  try {
    parseSweepSpec(text, "spec.yaml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(SweepSpec, GridAndCanonicalText) {
  const SweepSpec s = parseSweepSpec(kSpec, "spec.yaml");
  ASSERT_EQ(s.axes.size(), 2u);
  ASSERT_EQ(s.axes[0].values.size(), 3u);
  EXPECT_EQ(s.axes[0].values[1].number, 0.15);  // rounded to 12 significant digits, not 0.15000000000000002
  EXPECT_EQ(s.axes[0].values[2].number, 0.2);  // the range's end exactly
  EXPECT_EQ(s.points(), 6u);
  EXPECT_EQ(s.runs(), 6u * 4u * 2u);
  ASSERT_EQ(s.perturb.size(), 4u);  // sorted by key
  EXPECT_EQ(s.perturb[0].key, "push.impulse");
  EXPECT_EQ(s.perturb[1].key, "robot.com_offset");
  EXPECT_EQ(s.perturb[1].size, 3);
  EXPECT_TRUE(s.perturb[2].integer);  // sensors.latency_periods
  ASSERT_EQ(s.heatmaps.size(), 1u);   // default: the first two axes
  EXPECT_EQ(s.heatmaps[0].first, "target.wall_distance");
  const std::string canonical = s.canonicalYaml();
  EXPECT_EQ(parseSweepSpec(canonical, "canonical").canonicalYaml(), canonical);
  // Formatting does not make another sweep: the same spec written differently has the same canonical text.
  std::string other = kSpec;
  other.replace(other.find("from: 0.1,"), 10, "from: 0.10,");
  EXPECT_EQ(parseSweepSpec(other, "other").canonicalYaml(), canonical);
}

TEST(SweepSpec, BadSpecsNameTheKey) {
  const std::string base = "jumps: [squat-jump]\nmodes: [none]\n";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {base + "sedes: 3\n", "sedes"},
      {base + "planner: {axes: {target.height: []}}\n", "planner.axes.target.height"},
      {base + "planner: {axes: {target.height: {from: 0.9, to: 0.8, steps: 3}}}\n", "reversed range"},
      // 10^11 values (beyond int): refused by their count before it is converted to an integer
      {base + "planner: {axes: {target.height: {from: 0.8, to: 0.9, step: 1e-12}}}\n", "more than 100000 values"},
      {"jumps: [squat-jump]\nmodes: [none, magic]\n", "modes"},
      {base + "seeds: -3\n", "seeds"},
      {base + "planner: {axes: {target.hieght: [0.8]}}\n", "target.hieght"},
      {base + "planner: {axes: {target.height: [0.8, 9.0]}}\n", "planner.axes.target.height"},
      {base + "planner: {set: {cost.nope: 1}}\n", "planner.set"},
      {base + "simulation: {set: {world.frcition: 0.5}}\n", "world.frcition"},
      {base + "simulation: {perturb: {world.friction: {uniform: [0.5, 20]}}}\n", "simulation.perturb.world.friction"},
      {base + "simulation: {perturb: {world.friction: 0.5}}\n", "simulation.perturb.world.friction"},
      {base + "simulation: {perturb: {world.friction: {uniform: [1.0, 0.5]}}}\n", "reversed range"},
      {base + "simulation: {perturb: {robot.com_offset: {uniform: [[0, 0], [1, 1]]}}}\n", "robot.com_offset"},
      {base + "simulation: {perturb: {push.body: {choice: [pelvis]}}}\n", "push.body"},
      {base + "simulation: {set: {sensors.seed: 3}}\n", "sensors.seed"},
      {base + "simulation: {set: {controller.raibert.gains: [1, 2]}}\n", "controller"},
      {base + "planner: {axes: {target.height: [0.8, 0.8]}}\n", "listed twice"},
      {base + "heatmaps: [[target.height, contact.mu]]\n", "heatmaps"},
      {"modes: [none]\n", "jumps"},
      {"jumps: [moon-jump]\nmodes: [none]\n", "moon-jump"},
  };
  for (const auto& [text, expect] : cases) {
    const std::string m = message(text);
    EXPECT_NE(m.find("spec.yaml"), std::string::npos) << text << "\n-> " << m;
    EXPECT_NE(m.find(expect), std::string::npos) << text << "\n-> " << m;
  }
}
