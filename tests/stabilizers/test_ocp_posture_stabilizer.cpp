// ctest-labels: unit
// Stabilizer 3 (OCP postural task): the interpolation of eq. (posture_oc) is exact at the knots, continuous and
// periodic; the phase follows the sign of the pitch rate (forward for omega_y > 0, backward for < 0, held when
// inactive), wraps modulo 1 and is rate-limited; the blend goes from home to q*(tau_0); the right arm is the
// mirror image of the left; parameters are validated; update() through the whole-body controller with the
// stabilizer's own stack allocates nothing.
#include <gtest/gtest.h>

#include <cmath>

#include "common/error.hpp"
#include "common/yaml_reader.hpp"
#include "controller/whole_body_controller.hpp"
#include "model/robot_model.hpp"
#include "stabilizers/ocp_posture_stabilizer.hpp"
#include "support/allocation_counter.hpp"

using namespace centaur;
using data::RowMatrix;

namespace {

const std::string kModel = std::string(CENTAUR_SOURCE_DIR) + "/models/centauro/centauro.xml";

// A synthetic periodic plan: q_j(t) = a_j sin(2 pi t / T + phi_j) + c_j, M + 1 rows, h_y > 0 (sign set by `h`).
std::shared_ptr<data::ArmTrajectory> synthetic(int M = 100, double h = 1.0) {
  auto tr = std::make_shared<data::ArmTrajectory>();
  for (int i = 1; i <= 7; ++i) tr->joint_names.push_back("j_arm1_" + std::to_string(i));
  tr->period = 1.0;
  tr->t = Eigen::VectorXd::LinSpaced(M + 1, 0.0, 1.0);
  tr->q.resize(M + 1, 7);
  tr->h_ang.setZero(M + 1, 3);
  for (int k = 0; k <= M; ++k) {
    for (int j = 0; j < 7; ++j) tr->q(k, j) = 0.3 * std::sin(2 * M_PI * k / M + j) + 0.1 * j;
    tr->h_ang(k, 1) = h;
  }
  tr->q.row(M) = tr->q.row(0);  // exactly periodic
  tr->knot_x.resize(11, 14);
  for (int k = 0; k <= 10; ++k) tr->knot_x.row(k).head(7) = tr->q.row(10 * k);
  tr->knot_x.rightCols(7).setZero();
  tr->solve.status = "solved";
  return tr;
}

struct Robot {
  RobotModel model{kModel};
  std::vector<std::string> names = model.jointNames();
  Eigen::VectorXd home = model.homeJoints();
  int idx(const std::string& n) const { return model.jointIndex(n); }
};

RobotState stateWithPitchRate(const Robot& r, double wy) {
  RobotState s;
  s.resize(static_cast<Eigen::Index>(r.names.size()));
  s.q = r.home;
  s.imu_omega = Eigen::Vector3d(0.0, wy, 0.0);
  return s;
}

OcpPostureParams noBlend() {
  OcpPostureParams p;
  p.blend_time = 0.0;
  p.initial_phase = 0.0;
  return p;
}

}  // namespace

TEST(OcpPosture, InterpolationIsExactAtKnotsContinuousAndPeriodic) {
  const auto tr = synthetic(100);
  const RowMatrix& T = tr->q;
  const int M = 100;
  Eigen::VectorXd out(7), a(7), b(7);
  for (int k = 0; k <= M; k += 7) {
    interpolatePeriodic(T, static_cast<double>(k) / M, out);
    EXPECT_LT((out - T.row(k % M).transpose()).norm(), 1e-12) << "knot " << k;
  }
  // halfway between two knots: the mean of the two rows (linear in between, eq. posture_oc)
  interpolatePeriodic(T, 10.5 / M, out);
  EXPECT_LT((out - 0.5 * (T.row(10) + T.row(11)).transpose()).norm(), 1e-12);
  // continuous across every knot, including the wrap 1 -> 0
  for (int k = 0; k <= M; ++k) {
    interpolatePeriodic(T, static_cast<double>(k) / M - 1e-9, a);
    interpolatePeriodic(T, static_cast<double>(k) / M + 1e-9, b);
    EXPECT_LT((a - b).norm(), 1e-6) << "jump at knot " << k;
  }
  // periodic: tau and tau +- 1 give the same posture
  interpolatePeriodic(T, 0.37, a);
  interpolatePeriodic(T, 1.37, b);
  EXPECT_LT((a - b).norm(), 1e-12);
  interpolatePeriodic(T, -0.63, b);
  EXPECT_LT((a - b).norm(), 1e-12);
}

TEST(OcpPosture, PhaseFollowsTheSignOfThePitchRateAndWraps) {
  Robot r;
  OcpPostureStabilizer st(noBlend(), synthetic());
  st.start(r.names, r.home);
  EXPECT_DOUBLE_EQ(st.direction(), 1.0);
  const double dt = 0.001;
  // omega_y > 0: forward, by gamma_tau omega dt per tick
  for (int k = 0; k < 100; ++k) st.step(stateWithPitchRate(r, 0.5), dt, true);
  EXPECT_NEAR(st.phase(), 100 * 1.0 * 0.5 * dt, 1e-12);
  const double tau1 = st.phase();
  // omega_y < 0: backward
  for (int k = 0; k < 50; ++k) st.step(stateWithPitchRate(r, -0.5), dt, true);
  EXPECT_NEAR(st.phase(), tau1 - 50 * 0.5 * dt, 1e-12);
  // inactive or zero rate: held
  const double tau2 = st.phase();
  for (int k = 0; k < 50; ++k) st.step(stateWithPitchRate(r, 0.8), dt, false);
  for (int k = 0; k < 50; ++k) st.step(stateWithPitchRate(r, 0.0), dt, true);
  EXPECT_DOUBLE_EQ(st.phase(), tau2);
  // backwards past 0 wraps to just below 1
  for (int k = 0; k < 200; ++k) st.step(stateWithPitchRate(r, -0.5), dt, true);
  EXPECT_NEAR(st.phase(), tau2 - 0.1 + 1.0, 1e-9);
  EXPECT_GE(st.phase(), 0.0);
  EXPECT_LT(st.phase(), 1.0);
  // a huge rate is clamped to max_speed / period per second
  const double tau3 = st.phase();
  st.step(stateWithPitchRate(r, 1e6), dt, true);
  EXPECT_NEAR(st.phase(), std::fmod(tau3 + dt, 1.0), 1e-12);
  // NaN: held, reference stays finite
  const double tau4 = st.phase();
  st.step(stateWithPitchRate(r, std::nan("")), dt, true);
  EXPECT_DOUBLE_EQ(st.phase(), tau4);
  EXPECT_TRUE(st.postureReference().allFinite());
}

TEST(OcpPosture, APlanWithNegativeMomentumRunsBackwards) {
  Robot r;
  OcpPostureStabilizer st(noBlend(), synthetic(100, -2.0));
  st.start(r.names, r.home);
  EXPECT_DOUBLE_EQ(st.direction(), -1.0);
  for (int k = 0; k < 100; ++k) st.step(stateWithPitchRate(r, 0.5), 0.001, true);
  EXPECT_NEAR(st.phase(), 1.0 - 0.05, 1e-12);
}

TEST(OcpPosture, BothArmsReplayThePlanTheRightOneMirroredOtherJointsAtHome) {
  Robot r;
  const auto tr = synthetic();
  OcpPostureParams p = noBlend();
  p.initial_phase = 0.25;
  OcpPostureStabilizer st(p, tr);
  st.start(r.names, r.home);
  st.step(stateWithPitchRate(r, 0.0), 0.001, true);
  Eigen::VectorXd qs(7);
  interpolatePeriodic(tr->q, 0.25, qs);
  const auto s = data::armMirrorSigns();
  const Eigen::VectorXd& qd = st.postureReference();
  for (int j = 0; j < 7; ++j) {
    EXPECT_DOUBLE_EQ(qd[r.idx("j_arm1_" + std::to_string(j + 1))], qs[j]);
    EXPECT_DOUBLE_EQ(qd[r.idx("j_arm2_" + std::to_string(j + 1))], s[j] * qs[j]);
  }
  for (std::size_t i = 0; i < r.names.size(); ++i) {
    if (r.names[i].rfind("j_arm", 0) != 0) {
      EXPECT_EQ(qd[i], r.home[i]) << r.names[i];
    }
  }
  // The mirror signs are those of the home posture: left and right home values differ by exactly s.
  for (int j = 0; j < 7; ++j) {
    EXPECT_NEAR(r.home[r.idx("j_arm2_" + std::to_string(j + 1))], s[j] * r.home[r.idx("j_arm1_" + std::to_string(j + 1))],
                1e-6);
  }
  // The paper's form: interpolation between the OCP knots (11 rows here, every 10th sample).
  OcpPostureParams pk = p;
  pk.interpolation = "knots";
  OcpPostureStabilizer knots(pk, tr);
  knots.start(r.names, r.home);
  knots.step(stateWithPitchRate(r, 0.0), 0.001, true);
  const double x = 0.25 * 10;  // between knots 2 and 3
  const double qk = tr->knot_x(2, 0) + (x - 2) * (tr->knot_x(3, 0) - tr->knot_x(2, 0));
  EXPECT_NEAR(knots.postureReference()[r.idx("j_arm1_1")], qk, 1e-12);
  // Only the left arm: the right one stays at home.
  OcpPostureParams pl = p;
  pl.arms = "left";
  OcpPostureStabilizer left(pl, tr);
  left.start(r.names, r.home);
  left.step(stateWithPitchRate(r, 0.0), 0.001, true);
  EXPECT_EQ(left.postureReference()[r.idx("j_arm2_1")], r.home[r.idx("j_arm2_1")]);
  EXPECT_DOUBLE_EQ(left.postureReference()[r.idx("j_arm1_1")], qs[0]);
}

TEST(OcpPosture, BlendGoesSmoothlyFromHomeToTheTrajectoryAndHolds) {
  Robot r;
  const auto tr = synthetic();
  OcpPostureParams p;
  p.blend_time = 0.5;
  p.initial_phase = 0.6;
  OcpPostureStabilizer st(p, tr);
  st.start(r.names, r.home);
  Eigen::VectorXd target(7);
  interpolatePeriodic(tr->q, 0.6, target);
  const int i = r.idx("j_arm1_1");
  double prev = r.home[i], max_step = 0.0;
  st.step(stateWithPitchRate(r, 0.0), 0.0, false);  // dt = 0: nothing elapsed -> home
  EXPECT_DOUBLE_EQ(st.postureReference()[i], r.home[i]);
  for (int k = 0; k < 1000; ++k) {
    st.step(stateWithPitchRate(r, 0.3), 0.001, false);  // inactive: the phase stays at tau_0
    const double q = st.postureReference()[i];
    max_step = std::max(max_step, std::abs(q - prev));
    // monotone from home to the target
    EXPECT_LE(std::abs(q - target[0]), std::abs(prev - target[0]) + 1e-15);
    prev = q;
  }
  EXPECT_DOUBLE_EQ(st.phase(), 0.6);
  EXPECT_NEAR(prev, target[0], 1e-12);
  // smoothstep: the largest step is 1.5 x the mean step
  EXPECT_LT(max_step, 1.5 * std::abs(target[0] - r.home[i]) / 500.0 + 1e-12);
}

TEST(OcpPosture, AfterThePrimitiveTheArmsBlendToTheChosenTargetWithoutJumps) {
  Robot r;
  const auto tr = synthetic();
  const int i = r.idx("j_arm1_2"), k = r.idx("j_arm2_2");
  for (const std::string mode : {"home", "initial", "hold"}) {
    OcpPostureParams p;
    p.blend_time = 0.2;
    p.initial_phase = 0.1;
    p.after_end = mode;
    OcpPostureStabilizer st(p, tr);
    st.start(r.names, r.home);
    double prev = r.home[i], max_step = 0.0;
    auto tick = [&](double wy, bool active) {
      st.step(stateWithPitchRate(r, wy), 0.001, active);
      max_step = std::max(max_step, std::abs(st.postureReference()[i] - prev));
      prev = st.postureReference()[i];
    };
    for (int n = 0; n < 300; ++n) tick(0.0, false);  // start blend
    for (int n = 0; n < 400; ++n) tick(0.6, true);   // the primitive: phase 0.1 -> 0.34
    const double tau_end = st.phase();
    EXPECT_NEAR(tau_end, 0.1 + 0.4 * 0.6, 1e-9);
    const Eigen::VectorXd at_end = st.postureReference();
    for (int n = 0; n < 300; ++n) tick(0.6, false);  // ended: phase held, arms blend to the target
    EXPECT_DOUBLE_EQ(st.phase(), tau_end);
    Eigen::VectorXd expect(7);
    interpolatePeriodic(tr->q, mode == "initial" ? 0.1 : tau_end, expect);
    const double left = mode == "home" ? r.home[i] : expect[1];
    const double right = mode == "home" ? r.home[k] : -expect[1];
    EXPECT_NEAR(st.postureReference()[i], left, 1e-12) << mode;
    EXPECT_NEAR(st.postureReference()[k], right, 1e-12) << mode;
    if (mode == "hold") {
      EXPECT_NEAR(st.postureReference()[i], at_end[i], 1e-12);
    }
    // active again: back onto the trajectory at the held phase, smoothly
    for (int n = 0; n < 300; ++n) tick(0.0, true);
    interpolatePeriodic(tr->q, tau_end, expect);
    EXPECT_NEAR(st.postureReference()[i], expect[1], 1e-12) << mode;
    // no jump anywhere: per tick at most the planned speed or a blend step
    EXPECT_LT(max_step, 0.01) << mode;
  }
}

TEST(OcpPosture, ParametersAreValidated) {
  OcpPostureParams p;
  YAML::Node doc = loadYamlString(OcpPostureParams::defaultsYaml(), "<defaults>");
  YamlReader root(doc, "<defaults>");
  YamlReader sec = root.child("ocp");
  p.read(sec);
  sec.finish();
  EXPECT_EQ(p.flywheel_file, "");
  EXPECT_DOUBLE_EQ(p.gamma_tau, 1.0);
  EXPECT_DOUBLE_EQ(p.initial_phase, OcpPostureParams().initial_phase);  // the YAML text and the struct agree
  EXPECT_EQ(p.interpolation, "samples");
  auto bad = [](const std::string& text) {
    YAML::Node n = loadYamlString(text, "t.yaml");
    YamlReader rd(n, "t.yaml");
    OcpPostureParams q;
    q.read(rd);
    rd.finish();
  };
  EXPECT_THROW(bad("gamma_tau: -1"), InputError);
  EXPECT_THROW(bad("initial_phase: 1.0"), InputError);
  EXPECT_THROW(bad("arms: three"), InputError);
  EXPECT_THROW(bad("after_end: away"), InputError);
  EXPECT_THROW(bad("gamma: 1"), InputError);  // unknown key
  OcpPostureParams missing;
  missing.flywheel_file = "/nonexistent/arm.h5";
  EXPECT_THROW(OcpPostureStabilizer{missing}, InputError);
  // the stabilizer never plans: no file and no trajectory from the caller is an error naming the key
  try {
    OcpPostureStabilizer st{OcpPostureParams{}};
    ADD_FAILURE() << "an empty flywheel_file must be refused";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("ocp.flywheel_file"), std::string::npos) << e.what();
  }
  // a robot without the right arm's joints is refused at start()
  OcpPostureStabilizer ok(noBlend(), synthetic());
  EXPECT_THROW(ok.start({"j_arm1_1"}, Eigen::VectorXd::Zero(1)), InputError);
  // a plan that is not periodic is refused
  auto open = synthetic();
  open->q(0, 0) += 0.1;
  EXPECT_THROW(OcpPostureStabilizer(noBlend(), open), InputError);
}

TEST(OcpPosture, UpdateThroughTheWholeBodyControllerAllocatesNothing) {
  Robot r;
  OcpPostureParams p;
  p.blend_time = 0.2;
  OcpPostureStabilizer st(p, synthetic());
  WholeBodyParams wp;
  wp.stack_yaml = st.stackYaml(RobotFrames());
  WholeBodyController wbc(kModel, wp);
  RobotState s = stateWithPitchRate(r, 0.0);
  s.imu_acc = Eigen::Vector3d(0, 0, 9.81);
  JointCommand cmd;
  wbc.start(s, cmd);
  st.start(r.names, r.home);
  WholeBodyReferences refs;
  refs.resize(static_cast<int>(r.names.size()));
  const long before = centaur_test::heapAllocations();
  for (int k = 0; k < 1000; ++k) {
    s.t = 0.001 * (k + 1);
    s.imu_omega.y() = 0.8 * std::sin(0.01 * k);
    st.update(s, 0.001, k > 300, refs);
    wbc.setReferences(refs);
    wbc.tick(s, cmd);
    s.q = cmd.q_ref;
    s.qd = cmd.qd_ref;
  }
  EXPECT_EQ(centaur_test::heapAllocations() - before, 0);
  EXPECT_FALSE(wbc.inSafeMode());
  // the IK followed the posture reference: the left shoulder moved towards the plan
  EXPECT_TRUE(st.postureReference().allFinite());
  EXPECT_LT(std::abs(cmd.q_ref[r.idx("j_arm1_1")] - st.postureReference()[r.idx("j_arm1_1")]), 0.2);
}
