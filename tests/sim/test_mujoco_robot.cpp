// ctest-labels: sim physics
// The MuJoCo backend on a tiny purpose-built model (tests/testdata/sim_test_robot.xml): impedance law and
// saturation at every 2 kHz physics step, controller at exactly 1 kHz, measurement delay, IMU and
// ground-truth contact forces, wall placement.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "common/error.hpp"
#include "sim/mujoco_robot.hpp"

using namespace centaur;
using namespace centaur::sim;

namespace {

const std::string kModel = std::string(CENTAUR_SOURCE_DIR) + "/tests/testdata/sim_test_robot.xml";

SimSettings testSettings() {
  SimSettings s;
  s.model_path = kModel;
  return s;
}

/// Holds the arms at fixed references with constant gains; records every call.
class RecordingController : public Controller {
 public:
  explicit RecordingController(double kp = 20.0, double kd = 1.0) : kp_(kp), kd_(kd) {}
  void start(const RobotState& s, JointCommand& c) override {
    c.resize(s.q.size());
    times.reserve(100000);
    tick(s, c);
    times.clear();
  }
  void tick(const RobotState& s, JointCommand& c) noexcept override {
    times.push_back(s.t);
    last_q = s.q;
    c.q_ref.setConstant(0.2);
    c.qd_ref.setConstant(0.1);
    c.tau_ff.setConstant(0.5);
    c.kp.setConstant(kp_);
    c.kd.setConstant(kd_);
  }
  std::vector<double> times;
  Eigen::VectorXd last_q;

 private:
  double kp_, kd_;
};

/// Start `ctrl` on the robot's first measurement and run `periods` control periods; s is the last sample.
void startAndRun(MujocoRobot& robot, Controller& ctrl, RobotState& s, JointCommand& c, int periods) {
  s.resize(robot.numJoints());
  robot.read(s);
  ctrl.start(s, c);
  for (int k = 0; k < periods; ++k) robot.controlPeriod(ctrl, s, c);
}

}  // namespace

TEST(MujocoRobot, LoadsTestModelInActuatorOrder) {
  MujocoRobot robot(testSettings());
  ASSERT_EQ(robot.numJoints(), 2);
  EXPECT_EQ(robot.jointNames()[0], "joint_a");
  EXPECT_EQ(robot.jointNames()[1], "joint_b");
  EXPECT_DOUBLE_EQ(robot.effortLimits()[0], 5.0);
  EXPECT_DOUBLE_EQ(robot.effortLimits()[1], 2.0);
  EXPECT_DOUBLE_EQ(robot.positionUpper()[1], 1.0);
  RobotState s;
  s.resize(2);
  robot.read(s);
  EXPECT_DOUBLE_EQ(s.q[0], 0.3);  // keyframe `home`
  EXPECT_DOUBLE_EQ(s.q[1], -0.2);
  EXPECT_NEAR(robot.basePosition().z(), 0.2, 1e-12);
}

TEST(MujocoRobot, ImpedanceLawIsEvaluatedAtEveryPhysicsStepAndSaturated) {
  MujocoRobot robot(testSettings());
  JointCommand c;
  c.resize(2);
  c.q_ref << 0.1, 0.4;
  c.qd_ref << 0.3, -0.2;
  c.tau_ff << 0.7, -0.3;
  c.kp << 3.0, 2.0;
  c.kd << 0.4, 0.1;
  robot.write(c);
  Eigen::VectorXd q(2), qd(2);
  for (int step = 0; step < 200; ++step) {
    robot.jointPositions(q);
    robot.jointVelocities(qd);
    robot.physicsStep();
    for (int i = 0; i < 2; ++i) {
      const double law = c.tau_ff[i] + c.kp[i] * (c.q_ref[i] - q[i]) + c.kd[i] * (c.qd_ref[i] - qd[i]);
      const double lim = robot.effortLimits()[i];
      EXPECT_DOUBLE_EQ(robot.commandedTorque()[i], law) << "step " << step;
      EXPECT_DOUBLE_EQ(robot.appliedTorque()[i], std::clamp(law, -lim, lim)) << "step " << step;
      // The torque reaches the joint: MuJoCo's actuator generalized force on that dof.
      const int dof = robot.model()->jnt_dofadr[robot.model()->actuator_trnid[2 * i]];
      EXPECT_DOUBLE_EQ(robot.data()->qfrc_actuator[dof], robot.appliedTorque()[i]);
    }
  }
  // Saturation: a huge stiffness drives both joints to their effort limits, with the right signs.
  c.kp << 1e4, 1e4;
  c.kd.setZero();
  c.tau_ff.setZero();
  c.q_ref << 1.4, -0.9;
  robot.write(c);
  robot.jointPositions(q);
  robot.physicsStep();
  EXPECT_DOUBLE_EQ(robot.appliedTorque()[0], 5.0);
  EXPECT_DOUBLE_EQ(robot.appliedTorque()[1], -2.0);
  EXPECT_GT(std::abs(robot.commandedTorque()[0]), 5.0);
}

TEST(MujocoRobot, ControllerRunsAtExactly1kHzAndImpedanceAt2kHz) {
  MujocoRobot a(testSettings()), b(testSettings());
  RecordingController ctrl;
  RobotState s;
  s.resize(2);
  JointCommand c;
  a.read(s);
  ctrl.start(s, c);
  a.write(c);
  const int periods = 250;
  for (int k = 0; k < periods; ++k) a.controlPeriod(ctrl, s, c);
  ASSERT_EQ(ctrl.times.size(), static_cast<std::size_t>(periods));
  for (int k = 0; k < periods; ++k) EXPECT_NEAR(ctrl.times[k], 0.001 * k, 1e-12);
  EXPECT_NEAR(a.time(), 0.25, 1e-12);
  // The same constant command stepped by hand: two impedance evaluations per period give the same state.
  b.write(c);
  for (int k = 0; k < 2 * periods; ++k) b.physicsStep();
  Eigen::VectorXd qa(2), qb(2);
  a.jointPositions(qa);
  b.jointPositions(qb);
  EXPECT_EQ(qa, qb);
  EXPECT_EQ(a.appliedTorque(), b.appliedTorque());
}

TEST(MujocoRobot, MeasurementDelayIsWholeControlPeriods) {
  SimSettings delayed = testSettings();
  delayed.latency_periods = 3;
  MujocoRobot a(testSettings()), b(delayed);
  RecordingController ca, cb;
  RobotState sa, sb;
  sa.resize(2);
  sb.resize(2);
  JointCommand c1, c2;
  a.read(sa);
  b.read(sb);
  ca.start(sa, c1);
  cb.start(sb, c2);
  std::vector<double> ta, tb;
  std::vector<Eigen::VectorXd> qa, qb;
  // The controller's references do not depend on the state, so both robots move identically.
  for (int k = 0; k < 20; ++k) {
    a.controlPeriod(ca, sa, c1);
    b.controlPeriod(cb, sb, c2);
    qa.push_back(sa.q);
    qb.push_back(sb.q);
    ta.push_back(sa.t);
    tb.push_back(sb.t);
  }
  for (int k = 3; k < 20; ++k) {
    EXPECT_EQ(qb[k], qa[k - 3]) << k;
    EXPECT_DOUBLE_EQ(tb[k], ta[k - 3]) << k;
  }
  EXPECT_EQ(qb[0], qa[0]);  // before the line fills: the first sample
}

TEST(MujocoRobot, ImuAndGroundTruthContactForcesAtRest) {
  MujocoRobot robot(testSettings());
  RecordingController ctrl(50.0, 2.0);
  RobotState s;
  JointCommand c;
  startAndRun(robot, ctrl, s, c, 1500);  // 1.5 s: settled
  const double mass = 14.0, g = 9.81;
  Eigen::Matrix3Xd f(3, 4);
  robot.contactForces(f);
  const Eigen::Vector3d total = f.rowwise().sum();
  EXPECT_NEAR(total.z(), mass * g, 0.01 * mass * g);  // the ground carries the weight, pushing up
  EXPECT_NEAR(total.head<2>().norm(), 0.0, 0.01 * mass * g);
  for (int k = 0; k < 4; ++k) EXPECT_GT(f(2, k), 0.0) << "wheel " << k;
  // IMU at rest, level: orientation ~ identity, specific force = +g along z, no rotation.
  EXPECT_LT(s.imu_quat.angularDistance(Eigen::Quaterniond::Identity()), 1e-3);
  EXPECT_NEAR(s.imu_acc.z(), g, 0.05);
  EXPECT_NEAR(s.imu_acc.head<2>().norm(), 0.0, 0.05);
  EXPECT_LT(s.imu_omega.norm(), 1e-2);
  // At rest the motors carry the arms: applied torque = gravity torque (MuJoCo's bias force) per joint.
  for (int i = 0; i < 2; ++i) {
    const int dof = robot.model()->jnt_dofadr[robot.model()->actuator_trnid[2 * i]];
    EXPECT_NEAR(robot.appliedTorque()[i], robot.data()->qfrc_bias[dof], 1e-3) << i;
  }
  EXPECT_GT(std::abs(robot.appliedTorque()[0]), 1.0);  // joint_a holds a horizontal 1 kg arm
}

TEST(MujocoRobot, ImuQuaternionIsConvertedFromMujocoWxyz) {
  // Tilt the base about x by 0.3 rad (MuJoCo qpos quaternion order w, x, y, z) and compare.
  MujocoRobot robot(testSettings());
  mjData* d = robot.data();
  const Eigen::Quaterniond tilt(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()));
  d->qpos[3] = tilt.w();
  d->qpos[4] = tilt.x();
  d->qpos[5] = tilt.y();
  d->qpos[6] = tilt.z();
  d->qpos[2] = 1.0;
  RecordingController ctrl;
  RobotState s;
  s.resize(2);
  JointCommand c;
  ctrl.start(s, c);
  robot.controlPeriod(ctrl, s, c);
  EXPECT_LT(s.imu_quat.angularDistance(tilt), 1e-9);
  EXPECT_LT(robot.baseOrientation().angularDistance(tilt), 1e-4);  // one period later
}

TEST(MujocoRobot, WallFrontFaceIsPlacedAtWallX) {
  SimSettings s = testSettings();
  s.wall_x = 2.5;
  MujocoRobot robot(s);
  const int g = mj_name2id(robot.model(), mjOBJ_GEOM, "wall");
  ASSERT_GE(g, 0);
  const double front = robot.data()->geom_xpos[3 * g] + robot.model()->geom_size[3 * g];
  EXPECT_NEAR(front, 2.5, 1e-12);
}

TEST(MujocoRobot, NoiseIsSeededAndHasTheRequestedSpread) {
  SimSettings s = testSettings();
  s.noise.q = 0.01;
  s.noise.gyro = 0.02;
  MujocoRobot a(s), b(s);
  RecordingController ca, cb;
  RobotState sa, sb;
  sa.resize(2);
  sb.resize(2);
  JointCommand c1, c2;
  ca.start(sa, c1);
  cb.start(sb, c2);
  Eigen::VectorXd q(2);
  double sum2 = 0.0;
  const int N = 2000;
  for (int k = 0; k < N; ++k) {
    a.controlPeriod(ca, sa, c1);
    b.controlPeriod(cb, sb, c2);
    ASSERT_EQ(sa.q, sb.q);
    ASSERT_EQ(sa.imu_omega, sb.imu_omega);
    a.jointPositions(q);  // truth now differs from the sample by one period of motion; use the gyro
    sum2 += sa.imu_omega.squaredNorm() / 3.0;
  }
  EXPECT_NEAR(std::sqrt(sum2 / N), 0.02, 0.002);
}

TEST(MujocoRobot, EveryContactSolverReachesTheSameContactSolution) {
  // The test robot settles on its four wheels with each solver; they all solve the same convex contact problem
  // to the model's tolerance, so base pose, contact forces and joint torques agree closely after 0.5 s.
  std::vector<Eigen::Vector3d> base;
  std::vector<Eigen::Matrix3Xd> forces;
  for (const char* solver : {"newton", "cg", "pgs", "model"}) {
    SimSettings settings = testSettings();
    settings.solver = solver;
    MujocoRobot robot(settings);
    EXPECT_EQ(robot.model()->opt.solver, std::string(solver) == "cg"    ? mjSOL_CG
                                         : std::string(solver) == "pgs" ? mjSOL_PGS
                                                                        : mjSOL_NEWTON)
        << solver;  // the test model's own option is Newton
    RecordingController ctrl(50.0, 2.0);
    RobotState s;
    JointCommand c;
    startAndRun(robot, ctrl, s, c, 500);
    base.push_back(robot.basePosition());
    forces.emplace_back(3, 4);
    robot.contactForces(forces.back());
  }
  for (std::size_t i = 1; i < base.size(); ++i) {
    EXPECT_LT((base[i] - base[0]).norm(), 1e-6) << i;
    EXPECT_LT((forces[i] - forces[0]).cwiseAbs().maxCoeff(), 1e-2) << i;  // N, of ~34 N per wheel
  }
}

TEST(MujocoRobot, UnknownContactSolverIsAnInputError) {
  SimSettings settings = testSettings();
  settings.solver = "dantzig";
  EXPECT_THROW({ MujocoRobot robot(settings); }, InputError);
}

TEST(MujocoRobot, SampledAccelerometerIsTheLastStepsEvenWhenTheFirstStepSkipsIt) {
  // With 2 physics steps per period the first step of each period skips the accelerometer pass; the sample must
  // still be the accelerometer of the step just before it. Reference: the same physics with 1 step per period
  // (every step computes its sensors) and the same constant command, sampled after the same number of steps.
  SimSettings two = testSettings(), one = testSettings();
  one.control_decimation = 1;
  MujocoRobot a(two), b(one);
  RecordingController ca(50.0, 2.0), cb(50.0, 2.0);  // constant references: the same command at any rate
  RobotState sa, sb;
  JointCommand ka, kb;
  startAndRun(a, ca, sa, ka, 0);
  startAndRun(b, cb, sb, kb, 0);
  double max_acc = 0.0;
  for (int k = 0; k < 400; ++k) {  // 0.4 s: the robot drops onto its wheels and bounces (large accelerations)
    a.controlPeriod(ca, sa, ka);  // sa: the sample at the start of this period, after 2k steps
    b.controlPeriod(cb, sb, kb);  // sb: the sample after the same 2k steps
    ASSERT_EQ(sa.t, sb.t);
    ASSERT_EQ(sa.imu_acc, sb.imu_acc) << "period " << k;
    b.controlPeriod(cb, sb, kb);
    max_acc = std::max(max_acc, (sa.imu_acc - Eigen::Vector3d(0.0, 0.0, 9.81)).norm());
  }
  EXPECT_GT(max_acc, 0.1);  // the comparison saw real accelerations, not a resting robot only
}
