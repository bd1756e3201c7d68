// ctest-labels: sim integration
// The jumps on the simulated CENTAURO: both primitives planned once with the defaults, replayed by
// the JumpController with each stabilizer in MuJoCo. Asserted: the outcomes of docs/validation.md, finite
// commands, position references inside the joint ranges (and small soft-limit penetration in MuJoCo), the
// force distribution's feed-forward within the effort limits, and the replay's tracking of the planned
// pelvis -> wheel-centre vectors r_C during planned and detected stance.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "planner/jump_problem.hpp"
#include "data/primitive_io.hpp"
#include "sim/jump_observer.hpp"
#include "sim/mujoco_robot.hpp"
#include "sim/sim_config.hpp"
#include "sim/sim_runner.hpp"
#include "stabilizers/jump_controller.hpp"
#include "stabilizers/make_stabilizer.hpp"
#include "support/temp_dir.hpp"

using namespace centaur;
using namespace centaur::sim;

namespace {

class Jumps : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = std::make_unique<centaur_test::TempDir>("centaur-jumps");
    file_ = (dir_->path() / "primitives.h5").string();
    std::vector<data::Primitive> prims;
    for (const char* name : {"squat-jump", "half-squat-jump"}) {
      const planner::JumpProblem problem(planner::loadJumpConfig(name, "", {}));
      const planner::SolveResult r = problem.solve(false);
      ASSERT_TRUE(r.info.solved()) << name;
      prims.push_back(problem.toPrimitive(r));
    }
    data::writePrimitives(file_, prims);
  }
  static void TearDownTestSuite() { dir_.reset(); }

  static RunSummary run(const std::string& jump, const std::string& mode) {
    const Scenario* s = findScenario(jump);
    EXPECT_NE(s, nullptr);
    const RunSummary r = runScenario(*s, "", {}, {{"primitive", file_}, {"stabilizer", mode}}, RunOutputs{});
    std::printf("%s %-7s: %-15s peak pitch %5.2f deg, rms %4.2f deg, flight %.3f s, wall %.3f s, limit pen. %.3f rad\n",
                jump.c_str(), mode.c_str(), r.outcome.c_str(), r.peak_pitch_deg, r.extra.at("pitch_rms_deg"),
                r.extra.at("flight_time_s"), r.extra.count("wall_contact_s") ? r.extra.at("wall_contact_s") : 0.0,
                r.max_joint_limit_violation);
    return r;
  }

  static std::unique_ptr<centaur_test::TempDir> dir_;
  static std::string file_;
};
std::unique_ptr<centaur_test::TempDir> Jumps::dir_;
std::string Jumps::file_;

}  // namespace

TEST_F(Jumps, SquatJumpLandsUprightInEveryMode) {
  for (const char* mode : {"none", "raibert", "angmom", "ocp"}) {
    const RunSummary r = run("squat-jump", mode);
    EXPECT_EQ(r.outcome, "success") << mode;
    EXPECT_GT(r.extra.at("flight_time_s"), 0.2) << mode;   // it really jumps (plan: 0.27 s)
    EXPECT_LT(r.max_joint_limit_violation, 0.1) << mode;   // MuJoCo's soft limits at the landing impact
  }
}

TEST_F(Jumps, HalfSquatJumpReachesSteadyWallContact) {
  for (const char* mode : {"none", "raibert", "angmom", "ocp"}) {
    const RunSummary r = run("half-squat-jump", mode);
    EXPECT_EQ(r.outcome, "success") << mode;
    EXPECT_GE(r.extra.at("wall_contact_s"), 0.5) << mode;
    EXPECT_LT(r.max_joint_limit_violation, 0.1) << mode;
  }
}

TEST_F(Jumps, ReplayTracksThePlanAndCommandsStayFiniteAndWithinLimits) {
  SimConfig cfg = loadSimConfig(findScenario("squat-jump")->defaults_yaml, "", {});
  MujocoRobot robot(cfg.robot);
  YamlReader section = controllerSection(cfg);
  JumpControllerParams params;
  params.read(section);
  auto stabilizer = makeStabilizer("raibert", section);
  section.finish();
  params.wbc.dt = robot.controlPeriodSeconds();
  JumpController ctrl(cfg.robot.model_path, data::readPrimitive(file_, "squat-jump"), std::move(stabilizer), params);

  const mjModel* m = robot.model();
  const int pelvis = mj_name2id(m, mjOBJ_BODY, "pelvis");
  int site[4];
  for (int k = 0; k < 4; ++k) site[k] = mj_name2id(m, mjOBJ_SITE, ("wheel_centre_" + std::to_string(k + 1)).c_str());
  RobotState state;
  state.resize(robot.numJoints());
  JointCommand command;
  robot.read(state);
  ctrl.start(state, command);
  double sq = 0.0, worst = 0.0, ff_ratio = 0.0, qref_out = 0.0;
  long n = 0;
  const long periods = static_cast<long>(cfg.duration / robot.controlPeriodSeconds());
  for (long i = 0; i < periods; ++i) {
    robot.controlPeriod(ctrl, state, command);
    ASSERT_TRUE(command.q_ref.allFinite() && command.qd_ref.allFinite() && command.tau_ff.allFinite()) << i;
    ASSERT_FALSE(ctrl.wholeBody().inSafeMode()) << "tick " << i;
    for (Eigen::Index j = 0; j < command.tau_ff.size(); ++j) {
      ff_ratio = std::max(ff_ratio, std::abs(command.tau_ff[j]) / robot.effortLimits()[j]);
      qref_out = std::max({qref_out, robot.positionLower()[j] - command.q_ref[j], command.q_ref[j] - robot.positionUpper()[j]});
    }
    // r_C tracking during the replay, for wheels planned AND detected in stance
    const ReplaySample& s = ctrl.lastSample();
    if (!s.running) continue;
    const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> w_R_b(robot.data()->xmat + 9 * pelvis);
    const Eigen::Map<const Eigen::Vector3d> w_p_b(robot.data()->xpos + 3 * pelvis);
    for (int k = 0; k < 4; ++k) {
      if (!s.contact[k] || !ctrl.wholeBody().stance()[k]) continue;
      const Eigen::Map<const Eigen::Vector3d> w_p_c(robot.data()->site_xpos + 3 * site[k]);
      const double e = (w_R_b.transpose() * (w_p_c - w_p_b) - s.b_p_wheel.col(k)).norm();
      sq += e * e;
      worst = std::max(worst, e);
      ++n;
    }
  }
  const double rms = std::sqrt(sq / std::max(1L, n));
  std::printf("r_C tracking in stance: rms %.1f mm, max %.1f mm over %ld wheel samples; max |tau_ff|/limit %.2f; "
              "q_ref beyond range %.4f rad\n", 1e3 * rms, 1e3 * worst, n, ff_ratio, qref_out);
  EXPECT_GT(n, 4000);
  // [m] stated tolerance (docs/validation.md): the front legs cannot fully reach the stretched pose of the plan
  // (about 4 cm short for 0.5 s: the planner's box workspace is larger than the real legs' reach there), and
  // the landing impact compresses the legs for a few tens of ms.
  EXPECT_LT(rms, 0.035);
  EXPECT_LT(worst, 0.15);
  EXPECT_LE(ff_ratio, 1.0);
  EXPECT_LE(qref_out, 1e-6);
}
