// ctest-labels: sim unit
// The scenario API another module uses to add `centaur simulate <scenario>`: a static ScenarioRegistrar,
// scenario options with defaults / allowed values / required, the strict `controller:` section.
#include <gtest/gtest.h>

#include <algorithm>

#include "common/error.hpp"
#include "sim/scenario.hpp"
#include "sim/sim_runner.hpp"

using namespace centaur;
using namespace centaur::sim;

namespace {

std::map<std::string, std::string> g_seen_options;
double g_seen_gain = 0.0;

class ZeroController : public Controller {
 public:
  void start(const RobotState& s, JointCommand& c) override { c.resize(s.q.size()); }
  void tick(const RobotState&, JointCommand&) noexcept override {}
};

/// Counts periods and reports the highest pelvis; declares its own outcome.
class PeakObserver : public RunObserver {
 public:
  void observe(const MujocoRobot& robot, const RobotState&, const JointCommand&) override {
    ++periods_;
    peak_ = std::max(peak_, robot.basePosition().z());
  }
  std::map<std::string, double> summary() const override {
    return {{"observed_periods", periods_}, {"peak_pelvis_height_m", peak_}};
  }
  std::string outcome() const override { return "observed"; }

 private:
  double periods_ = 0.0, peak_ = -1.0;
};

Scenario withObserver(Scenario s) {
  s.make_observer = [](ScenarioContext&) -> std::unique_ptr<RunObserver> { return std::make_unique<PeakObserver>(); };
  return s;
}

const ScenarioRegistrar kRegistrar{withObserver(Scenario{
    "test-scenario", "a scenario registered by a test",
    "duration: 0.05\nmodel: " + std::string(CENTAUR_SOURCE_DIR) +
        "/tests/testdata/sim_test_robot.xml\ncontroller: {gain: 2.0}\n",
    {{"primitive", "primitive file", "", {}, true},
     {"stabilizer", "stabilizer", "none", {"none", "raibert", "angmom", "ocp"}, false}},
    [](ScenarioContext& ctx) -> std::unique_ptr<Controller> {
      ctx.controller_config.get("gain", g_seen_gain, 0.0, 10.0);
      ctx.controller_config.finish();
      g_seen_options = ctx.options;
      return std::make_unique<ZeroController>();
    }})};

}  // namespace

TEST(ScenarioRegistry, BuiltInStandComesFirstAndRegisteredScenariosAreFound) {
  ASSERT_FALSE(scenarios().empty());
  EXPECT_EQ(scenarios().front().name, "stand");
  ASSERT_NE(findScenario("test-scenario"), nullptr);
  EXPECT_EQ(findScenario("no-such-scenario"), nullptr);
}

TEST(ScenarioRegistry, OptionsGetDefaultsAndAreChecked) {
  const Scenario& s = *findScenario("test-scenario");
  // (fall criteria off: the unactuated test robot would "fall", and a fall is never replaced by the observer)
  const RunSummary r = runScenario(s, "", {"controller.gain=3.5", "outcome.fall_height=0", "outcome.fall_tilt_deg=180"},
                                   {{"primitive", "jump.h5"}}, RunOutputs{});
  EXPECT_EQ(r.control_periods, 50);
  EXPECT_EQ(g_seen_options.at("primitive"), "jump.h5");
  EXPECT_EQ(g_seen_options.at("stabilizer"), "none");  // default filled in
  EXPECT_DOUBLE_EQ(g_seen_gain, 3.5);
  EXPECT_EQ(r.outcome, "observed") << "fall at " << r.fall_time_s << " s, final height " << r.final_pelvis_height_m;
  EXPECT_DOUBLE_EQ(r.extra.at("observed_periods"), 50.0);
  EXPECT_GT(r.extra.at("peak_pelvis_height_m"), 0.15);  // the test robot's pelvis starts at 0.2 m
  EXPECT_THROW(runScenario(s, "", {}, {}, RunOutputs{}), InputError);  // --primitive is required
  EXPECT_THROW(runScenario(s, "", {}, {{"primitive", "a.h5"}, {"stabilizer", "magic"}}, RunOutputs{}), InputError);
  EXPECT_THROW(runScenario(s, "", {}, {{"primitive", "a.h5"}, {"bogus", "1"}}, RunOutputs{}), InputError);
  EXPECT_THROW(runScenario(s, "", {"controller.gian=1"}, {{"primitive", "a.h5"}}, RunOutputs{}), InputError);
}
