// ctest-labels: unit physics
// Whole-body controller and its robot tasks on CENTAURO, without a simulator:
// task Jacobians against central finite differences, the YAML stack, zero allocations over 1000 ticks, safe
// mode on NaN input, and strict priority on the robot (the posture level never worsens the feet).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>

#include "common/error.hpp"
#include "common/yaml_reader.hpp"
#include "controller/robot_tasks.hpp"
#include "controller/task_angular_momentum.hpp"
#include "controller/task_cartesian.hpp"
#include "controller/task_com.hpp"
#include "controller/task_pelvis_angular_velocity.hpp"
#include "controller/task_postural.hpp"
#include "controller/whole_body_controller.hpp"
#include "support/allocation_counter.hpp"

using namespace centaur;

namespace {
const std::string kModel = std::string(CENTAUR_SOURCE_DIR) + "/models/centauro/centauro.xml";
const std::string kStack = std::string(CENTAUR_SOURCE_DIR) + "/config/stack_stand.yaml";

// q (+) eps v with RobotModel's conventions: world linear velocity, base-frame angular velocity.
Eigen::VectorXd integrate(const Eigen::VectorXd& q, const Eigen::VectorXd& v, double eps) {
  Eigen::VectorXd out = q;
  out.head<3>() += eps * v.head<3>();
  const Eigen::Quaterniond quat(q[3], q[4], q[5], q[6]);
  const Eigen::Vector3d w = eps * v.segment<3>(3);
  Eigen::Quaterniond dq(Eigen::AngleAxisd(w.norm(), w.norm() > 0 ? Eigen::Vector3d(w.normalized()) : Eigen::Vector3d::UnitX()));
  const Eigen::Quaterniond r = (quat * dq).normalized();
  out[3] = r.w();
  out[4] = r.x();
  out[5] = r.y();
  out[6] = r.z();
  out.tail(v.size() - 6) += eps * v.tail(v.size() - 6);
  return out;
}

Eigen::VectorXd randomConfiguration(const RobotModel& m, unsigned seed) {
  std::srand(seed);
  Eigen::VectorXd q(m.nq());
  q.head<3>() << 0.1, -0.2, 0.7;
  const Eigen::Quaterniond r = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()));
  q[3] = r.w();
  q[4] = r.x();
  q[5] = r.y();
  q[6] = r.z();
  q.tail(m.numJoints()) = m.homeJoints() + 0.1 * Eigen::VectorXd::Random(m.numJoints());
  return q;
}

RobotState homeState(const RobotModel& m) {
  RobotState s;
  s.resize(m.numJoints());
  s.q = m.homeJoints();
  s.imu_acc = Eigen::Vector3d(0, 0, 9.81);
  return s;
}

WholeBodyParams params(const std::string& stack = kStack) {
  WholeBodyParams p;
  p.stack_file = stack;
  return p;
}
}  // namespace

TEST(RobotTasks, CartesianRelativeJacobianMatchesFiniteDifferencesIncludingTheBaseTwist) {
  RobotModel m(kModel);
  const Eigen::VectorXd q = randomConfiguration(m, 3);
  Eigen::VectorXd v = Eigen::VectorXd::Random(m.nv());
  m.update(q, Eigen::VectorXd::Zero(m.nv()));
  CartesianTask t("foot", m, "pelvis", "wheel_centre_2", true);
  t.holdCurrent();
  t.update();
  const Eigen::VectorXd Av = t.A() * v;
  EXPECT_EQ(t.A().leftCols<6>().norm(), 0.0);  // a relative pose does not depend on the base twist
  const double eps = 1e-6;
  Eigen::Vector3d pp, pm;
  Eigen::Matrix3d Rp, Rm;
  m.update(integrate(q, v, eps), Eigen::VectorXd::Zero(m.nv()));
  t.currentPose(pp, Rp);
  m.update(integrate(q, v, -eps), Eigen::VectorXd::Zero(m.nv()));
  t.currentPose(pm, Rm);
  const Eigen::Vector3d dp = (pp - pm) / (2 * eps);
  const Eigen::AngleAxisd daa(Rp * Rm.transpose());
  const Eigen::Vector3d dw = daa.angle() * daa.axis() / (2 * eps);
  EXPECT_LT((Av.head<3>() - dp).norm(), 1e-6 * (1 + dp.norm())) << Av.head<3>().transpose() << " vs " << dp.transpose();
  EXPECT_LT((Av.tail<3>() - dw).norm(), 1e-6 * (1 + dw.norm()));
  EXPECT_GT(dp.norm(), 1e-2);  // a real motion was tested
}

TEST(RobotTasks, WorldCartesianAndPelvisAngularVelocityJacobiansMatchFiniteDifferences) {
  RobotModel m(kModel);
  const Eigen::VectorXd q = randomConfiguration(m, 5);
  const Eigen::VectorXd v = Eigen::VectorXd::Random(m.nv());
  m.update(q, Eigen::VectorXd::Zero(m.nv()));
  CartesianTask foot("foot", m, "world", "wheel_centre_1", false);
  PelvisAngularVelocityTask pelvis("pelvis", m);
  foot.update();
  pelvis.update();
  const Eigen::Vector3d Av = foot.A() * v, Wv = pelvis.A() * v;
  const double eps = 1e-6;
  Eigen::Vector3d pp, pm;
  Eigen::Matrix3d Rp, Rm;
  m.update(integrate(q, v, eps), Eigen::VectorXd::Zero(m.nv()));
  foot.currentPose(pp, Rp);
  const Eigen::Matrix3d Bp = m.framePose(m.frameId("pelvis")).linear();
  m.update(integrate(q, v, -eps), Eigen::VectorXd::Zero(m.nv()));
  foot.currentPose(pm, Rm);
  const Eigen::Matrix3d Bm = m.framePose(m.frameId("pelvis")).linear();
  EXPECT_LT((Av - (pp - pm) / (2 * eps)).norm(), 1e-6 * (1 + Av.norm()));
  const Eigen::AngleAxisd daa(Bp * Bm.transpose());  // world-frame angular velocity of the pelvis
  EXPECT_LT((Wv - daa.angle() * daa.axis() / (2 * eps)).norm(), 1e-6 * (1 + Wv.norm()));
  // A x = omega_d exactly with lambda 1
  pelvis.setReference(Eigen::Vector3d(0.1, -0.2, 0.3));
  pelvis.update();
  EXPECT_NEAR((pelvis.b() - Eigen::Vector3d(0.1, -0.2, 0.3)).norm(), 0.0, 1e-15);
}

TEST(RobotTasks, AngularMomentumRowsArePhysicalAndPosturalPointsToTheReference) {
  RobotModel m(kModel);
  const Eigen::VectorXd q = randomConfiguration(m, 7);
  Eigen::VectorXd v = Eigen::VectorXd::Zero(m.nv());
  v.head<3>() << 1.0, -2.0, 0.5;  // pure base translation: no angular momentum about the CoM
  m.update(q, v);
  AngularMomentumTask h("h", m);
  h.update();
  EXPECT_LT((h.A() * v).norm(), 1e-9);
  v = Eigen::VectorXd::Random(m.nv());
  m.update(q, v);
  h.update();
  EXPECT_LT((h.A() * v - m.centroidalMomentum().tail<3>()).norm(), 1e-9);
  PosturalTask p("p", m, {m.jointIndex("torso_yaw"), m.jointIndex("j_arm1_1")});
  Eigen::VectorXd qd = q.tail(m.numJoints());
  qd[m.jointIndex("torso_yaw")] += 0.2;
  p.setReference(qd);
  p.update();
  EXPECT_NEAR(p.b()[0], 0.2, 1e-12);
  EXPECT_NEAR(p.b()[1], 0.0, 1e-12);
  EXPECT_EQ(p.A()(0, 6 + m.jointIndex("torso_yaw")), 1.0);
}

TEST(RobotTasks, StackYamlLoadsWithEveryRegisteredTypeAndRejectsUnknownKeys) {
  RobotModel m(kModel);
  TaskRegistry reg;
  registerRobotTasks(reg, m, 0.001);
  for (const char* t : {"Cartesian", "PelvisAngularVelocity", "Postural", "AngularMomentum", "Com"})
    EXPECT_TRUE(reg.hasTask(t)) << t;
  const LoadedStack s = loadStack(loadYamlFile(kStack), kStack, reg);
  EXPECT_EQ(s.stack.levels.size(), 3u);
  EXPECT_EQ(s.stack.constraints.size(), 2u);
  EXPECT_EQ(s.stack.levels[0].size(), 12);
  EXPECT_EQ(s.stack.levels[2].size(), 3 + m.numJoints());
  const YAML::Node bad = loadYamlString(
      "stack: [[f]]\nf: {type: Cartesian, distal_link: wheel_centre_1, colour: red}\n", "bad.yaml");
  EXPECT_THROW(loadStack(bad, "bad.yaml", reg), InputError);
  const YAML::Node frame = loadYamlString("stack: [[f]]\nf: {type: Cartesian, distal_link: nowhere}\n", "f.yaml");
  EXPECT_THROW(loadStack(frame, "f.yaml", reg), InputError);
  const YAML::Node com = loadYamlString(
      "stack: [[c], [p]]\nc: {type: Com}\np: {type: Postural, joints: [torso_yaw]}\n", "c.yaml");
  EXPECT_EQ(loadStack(com, "c.yaml", reg).stack.levels.size(), 2u);
}

TEST(WholeBodyController, ThousandTicksWithoutHeapAllocation) {
  RobotModel m(kModel);
  WholeBodyController c(kModel, params());
  RobotState s = homeState(m);
  JointCommand cmd;
  c.start(s, cmd);
  const Eigen::VectorXd home = m.homeJoints();
  Eigen::VectorXd q_d = home;
  const int arm = m.jointIndex("j_arm1_1");
  const long before = centaur_test::heapAllocations();
  for (int k = 0; k < 1000; ++k) {
    s.t = 0.001 * (k + 1);
    s.q = cmd.q_ref;
    s.q[0] += 1e-3 * std::sin(0.01 * k);
    s.qd = cmd.qd_ref;
    s.tau = cmd.tau_ff;
    q_d[arm] = home[arm] + 0.2 * std::sin(0.005 * k);
    c.setPostureReference(q_d);
    c.setPelvisAngularVelocity(Eigen::Vector3d(0, 0, 0));
    c.tick(s, cmd);
  }
  EXPECT_EQ(centaur_test::heapAllocations() - before, 0);
  EXPECT_EQ(c.status(), WholeBodyStatus::kOk);
  EXPECT_EQ(c.counters().ticks, 1001);
  EXPECT_EQ(c.counters().qp_failures, 0);
  EXPECT_TRUE(cmd.q_ref.allFinite());
  // the arm followed its posture reference (the IK did something)
  EXPECT_GT(std::abs(cmd.q_ref[m.jointIndex("j_arm1_1")] - m.homeJoints()[m.jointIndex("j_arm1_1")]), 0.05);
}

TEST(WholeBodyController, NanInTheStateEntersSafeModeWithAFiniteDampedCommand) {
  RobotModel m(kModel);
  WholeBodyController c(kModel, params());
  RobotState s = homeState(m);
  JointCommand cmd;
  c.start(s, cmd);
  for (int k = 0; k < 10; ++k) {
    s.t += 0.001;
    c.tick(s, cmd);
  }
  ASSERT_EQ(c.status(), WholeBodyStatus::kOk);
  const Eigen::VectorXd q_good = cmd.q_ref, tau_good = cmd.tau_ff, kd_nominal = cmd.kd;
  // the nominal feed-forward carries the weight: tau_ff is not zero on the legs
  EXPECT_GT(tau_good.norm(), 10.0);
  s.t += 0.001;
  s.q[3] = std::numeric_limits<double>::quiet_NaN();
  c.tick(s, cmd);
  EXPECT_EQ(c.status(), WholeBodyStatus::kSafeInvalidInput);
  EXPECT_TRUE(c.inSafeMode());
  for (const Eigen::VectorXd* v : {&cmd.q_ref, &cmd.qd_ref, &cmd.tau_ff, &cmd.kp, &cmd.kd}) EXPECT_TRUE(v->allFinite());
  EXPECT_EQ((cmd.q_ref - q_good).norm(), 0.0);
  EXPECT_EQ(cmd.qd_ref.norm(), 0.0);
  EXPECT_EQ((cmd.tau_ff - tau_good).norm(), 0.0);
  EXPECT_NEAR((cmd.kd - c.params().safe_kd_scale * kd_nominal).norm(), 0.0, 1e-12);
  EXPECT_EQ(c.counters().invalid_inputs, 1);
  // latched: a valid state keeps the safe command until resume()
  s.q = m.homeJoints();
  s.imu_omega.x() = std::numeric_limits<double>::infinity();
  c.tick(s, cmd);
  s.imu_omega.setZero();
  c.tick(s, cmd);
  EXPECT_TRUE(c.inSafeMode());
  EXPECT_EQ(c.counters().invalid_inputs, 2);
  EXPECT_EQ(c.counters().safe_ticks, 3);
  c.resume();
  c.tick(s, cmd);
  EXPECT_EQ(c.status(), WholeBodyStatus::kOk);
  EXPECT_NEAR((cmd.kd - kd_nominal).norm(), 0.0, 1e-12);
  EXPECT_TRUE(cmd.q_ref.allFinite());
}

TEST(WholeBodyController, PostureLevelNeverWorsensTheFeet) {
  // Closed loop with perfect tracking (q = q_ref): the feet are asked to go 4 cm down (pelvis up) and
  // forward while the posture pulls the legs somewhere else. The feet error with the posture level must equal
  // the one without it, tick by tick; and the posture must actually act (the arms move).
  RobotModel m(kModel);
  const std::string no_posture = ::testing::TempDir() + "/stack_no_posture.yaml";
  {
    std::ofstream f(no_posture);
    f << "stack:\n  - [wheel_1, wheel_2, wheel_3, wheel_4]\n  - [pelvis]\n"
         "constraints: [joint_limits, velocity_limits]\n"
         "wheel_1: {type: Cartesian, base_link: pelvis, distal_link: wheel_centre_1, lambda: 20.0}\n"
         "wheel_2: {type: Cartesian, base_link: pelvis, distal_link: wheel_centre_2, lambda: 20.0}\n"
         "wheel_3: {type: Cartesian, base_link: pelvis, distal_link: wheel_centre_3, lambda: 20.0}\n"
         "wheel_4: {type: Cartesian, base_link: pelvis, distal_link: wheel_centre_4, lambda: 20.0}\n"
         "pelvis: {type: PelvisAngularVelocity}\n"
         "joint_limits: {type: JointPositionLimits, scaling: 0.5}\nvelocity_limits: {type: JointVelocityLimits}\n";
  }
  WholeBodyParams pa = params(), pb = params(no_posture);
  pa.use_contact_detector = pb.use_contact_detector = false;
  WholeBodyController a(kModel, pa), b(kModel, pb);
  RobotState sa = homeState(m), sb = homeState(m);
  JointCommand ca, cb;
  a.start(sa, ca);
  b.start(sb, cb);
  Eigen::Matrix<double, 3, 4> feet;
  for (int k = 0; k < 4; ++k) {
    Eigen::Vector3d p;
    Eigen::Matrix3d R;
    auto t = std::dynamic_pointer_cast<CartesianTask>(a.stack().tasks.at("wheel_" + std::to_string(k + 1)));
    t->currentPose(p, R);
    feet.col(k) = p + Eigen::Vector3d(0.03, 0.0, -0.04);
  }
  a.setFootReferences(feet);
  b.setFootReferences(feet);
  Eigen::VectorXd q_d = m.homeJoints().array() + 0.3;  // conflicts with the feet on the legs
  a.setPostureReference(q_d);
  double max_diff = 0.0, err_a = 0.0, err_b = 0.0;
  for (int k = 0; k < 300; ++k) {
    sa.t = sb.t = 0.001 * (k + 1);
    sa.q = ca.q_ref;
    sb.q = cb.q_ref;
    a.tick(sa, ca);
    b.tick(sb, cb);
    ASSERT_EQ(a.status(), WholeBodyStatus::kOk);
    ASSERT_EQ(b.status(), WholeBodyStatus::kOk);
    err_a = err_b = 0.0;
    for (int f = 0; f < 4; ++f) {
      auto ta = std::dynamic_pointer_cast<CartesianTask>(a.stack().tasks.at("wheel_" + std::to_string(f + 1)));
      auto tb = std::dynamic_pointer_cast<CartesianTask>(b.stack().tasks.at("wheel_" + std::to_string(f + 1)));
      err_a += ta->positionError();
      err_b += tb->positionError();
    }
    max_diff = std::max(max_diff, err_a - err_b);
  }
  // Never worse, up to the second-order effect of integrating along different joint paths (the two runs move
  // the legs' redundant joints differently): < 0.1 mm summed over the four feet, against 4 x 5 cm at the start.
  std::printf("feet error sum: with posture %.3e m, without %.3e m, max (with - without) %.3e m\n", err_a, err_b,
              max_diff);
  EXPECT_LT(max_diff, 1e-4);
  EXPECT_LT(err_a, 0.02 * 0.05 * 4);  // and the feet converged (start: 5 cm each)
  const int arm = m.jointIndex("j_arm1_1");
  EXPECT_GT(std::abs(ca.q_ref[arm] - m.homeJoints()[arm]), 0.1);  // posture acted on the free joints
  EXPECT_LT(std::abs(cb.q_ref[arm] - m.homeJoints()[arm]), 1e-3);
}

TEST(WholeBodyController, FastStackGivesTheSameCommandsAsThePaperStack) {
  // config/stack_stand_fast.yaml merges the feet and pelvis levels (they act on disjoint columns): the same
  // commands, tick by tick, with moving feet, pelvis rotation and posture references.
  RobotModel m(kModel);
  WholeBodyParams pa = params(), pb = params(std::string(CENTAUR_SOURCE_DIR) + "/config/stack_stand_fast.yaml");
  pa.use_contact_detector = pb.use_contact_detector = false;
  WholeBodyController a(kModel, pa), b(kModel, pb);
  EXPECT_EQ(a.hqp().numLevels(), 3);
  EXPECT_EQ(b.hqp().numLevels(), 2);
  RobotState s = homeState(m);
  JointCommand ca, cb;
  a.start(s, ca);
  b.start(s, cb);
  Eigen::Matrix<double, 3, 4> feet;
  for (int k = 0; k < 4; ++k) {
    Eigen::Vector3d p;
    Eigen::Matrix3d R;
    std::dynamic_pointer_cast<CartesianTask>(a.stack().tasks.at("wheel_" + std::to_string(k + 1)))->currentPose(p, R);
    feet.col(k) = p + Eigen::Vector3d(0.0, 0.0, -0.02);
  }
  a.setFootReferences(feet);
  b.setFootReferences(feet);
  a.setPelvisAngularVelocity(Eigen::Vector3d(0.0, 0.1, 0.0));
  b.setPelvisAngularVelocity(Eigen::Vector3d(0.0, 0.1, 0.0));
  Eigen::VectorXd q_d = m.homeJoints();
  q_d[m.jointIndex("j_arm2_2")] -= 0.3;
  a.setPostureReference(q_d);
  b.setPostureReference(q_d);
  double max_dqd = 0.0, max_dx = 0.0;
  for (int k = 0; k < 200; ++k) {
    s.t = 0.001 * (k + 1);
    s.q = ca.q_ref;
    a.tick(s, ca);
    b.tick(s, cb);
    ASSERT_EQ(a.status(), WholeBodyStatus::kOk);
    ASSERT_EQ(b.status(), WholeBodyStatus::kOk);
    max_dqd = std::max(max_dqd, (ca.qd_ref - cb.qd_ref).lpNorm<Eigen::Infinity>());
    max_dx = std::max(max_dx, (a.solution() - b.solution()).lpNorm<Eigen::Infinity>());
  }
  EXPECT_LT(max_dqd, 1e-6);
  EXPECT_LT(max_dx, 1e-6);
  EXPECT_NEAR(a.solution()[4], 0.1, 1e-6);  // b_omega_y = 0.1 (the pelvis is level: w_R_b = I)
}

TEST(WholeBodyController, ComShiftWithWheelsFixedInTheWorld) {
  // A stack with the wheels fixed in the WORLD (Cartesian base_link: world, so A has base columns) above a CoM
  // task: asked to move the CoM 2 cm forward, the joints move, the estimator's base follows from the anchored
  // wheels (perfect tracking q = q_ref), the CoM arrives and the wheels do not move.
  RobotModel m(kModel);
  const std::string file = ::testing::TempDir() + "/stack_com.yaml";
  {
    std::ofstream f(file);
    f << "stack:\n  - [w1, w2, w3, w4, pelvis]\n  - [com]\n  - [posture]\n"
         "constraints: [joint_limits, velocity_limits]\n"
         "w1: {type: Cartesian, base_link: world, distal_link: wheel_centre_1, lambda: 20.0}\n"
         "w2: {type: Cartesian, base_link: world, distal_link: wheel_centre_2, lambda: 20.0}\n"
         "w3: {type: Cartesian, base_link: world, distal_link: wheel_centre_3, lambda: 20.0}\n"
         "w4: {type: Cartesian, base_link: world, distal_link: wheel_centre_4, lambda: 20.0}\n"
         "pelvis: {type: PelvisAngularVelocity}\n"
         "com: {type: Com, lambda: 10.0}\n"
         "posture: {type: Postural, lambda: 2.0, weight: 0.01}\n"
         "joint_limits: {type: JointPositionLimits, scaling: 0.5}\nvelocity_limits: {type: JointVelocityLimits}\n";
  }
  WholeBodyParams p = params(file);
  p.use_contact_detector = false;
  WholeBodyController c(kModel, p);
  RobotState s = homeState(m);
  JointCommand cmd;
  c.start(s, cmd);
  auto com = std::dynamic_pointer_cast<ComTask>(c.stack().tasks.at("com"));
  ASSERT_TRUE(com);
  const Eigen::Vector3d com0 = c.ikModel().com();
  EXPECT_LT((com->reference() - com0).norm(), 1e-12);  // held at start
  std::array<Eigen::Vector3d, 4> wheel0;
  for (int k = 0; k < 4; ++k) wheel0[k] = c.ikModel().framePose(m.frameId("wheel_centre_" + std::to_string(k + 1))).translation();
  com->setReference(com0 + Eigen::Vector3d(0.02, 0.0, 0.0));
  for (int k = 0; k < 1000; ++k) {
    s.t = 0.001 * (k + 1);
    s.q = cmd.q_ref;
    c.tick(s, cmd);
    ASSERT_EQ(c.status(), WholeBodyStatus::kOk);
  }
  const Eigen::Vector3d com1 = c.ikModel().com();
  std::printf("CoM moved by %.4f %.4f %.4f m\n", com1.x() - com0.x(), com1.y() - com0.y(), com1.z() - com0.z());
  EXPECT_NEAR(com1.x() - com0.x(), 0.02, 1e-3);
  EXPECT_NEAR(com1.y() - com0.y(), 0.0, 1e-3);
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector3d w = c.ikModel().framePose(m.frameId("wheel_centre_" + std::to_string(k + 1))).translation();
    EXPECT_LT((w - wheel0[k]).norm(), 2e-3) << "wheel " << k + 1;
  }
}

TEST(WholeBodyController, FailedQpEntersSafeModeAndResumeRecovers) {
  // A non-finite reference reaches the HQP (invalid input -> failed solve): safe mode kSafeQpFailed with the
  // last good posture, zero velocity and raised damping; after a valid reference and resume() it is nominal.
  RobotModel m(kModel);
  WholeBodyController c(kModel, params());
  RobotState s = homeState(m);
  JointCommand cmd;
  c.start(s, cmd);
  for (int k = 0; k < 5; ++k) {
    s.t += 0.001;
    c.tick(s, cmd);
  }
  const Eigen::VectorXd q_good = cmd.q_ref, kd_nominal = cmd.kd;
  c.setPelvisAngularVelocity(Eigen::Vector3d(std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0));
  s.t += 0.001;
  c.tick(s, cmd);
  EXPECT_EQ(c.status(), WholeBodyStatus::kSafeQpFailed);
  EXPECT_EQ(c.counters().qp_failures, 1);
  EXPECT_NE(c.lastQpStatus(), QpStatus::kOptimal);
  for (const Eigen::VectorXd* v : {&cmd.q_ref, &cmd.qd_ref, &cmd.tau_ff, &cmd.kd}) EXPECT_TRUE(v->allFinite());
  EXPECT_EQ((cmd.q_ref - q_good).norm(), 0.0);
  EXPECT_EQ(cmd.qd_ref.norm(), 0.0);
  EXPECT_GT(cmd.kd.sum(), 2.0 * kd_nominal.sum());
  c.setPelvisAngularVelocity(Eigen::Vector3d::Zero());
  s.t += 0.001;
  c.tick(s, cmd);
  EXPECT_TRUE(c.inSafeMode());  // latched
  c.resume();
  s.t += 0.001;
  c.tick(s, cmd);
  EXPECT_EQ(c.status(), WholeBodyStatus::kOk);
  EXPECT_EQ(c.lastQpStatus(), QpStatus::kOptimal);
  EXPECT_EQ((cmd.kd - kd_nominal).norm(), 0.0);
}

TEST(WholeBodyController, QpAnswerFailingItsKktCheckIsNeverUsed) {
  // A level's QP answer that fails the solver's KKT check (here forced by a tolerance no answer can meet) is a
  // failed HQP solve: safe mode with the last good command, never the rejected answer; resume() recovers.
  RobotModel m(kModel);
  WholeBodyController c(kModel, params());
  RobotState s = homeState(m);
  JointCommand cmd;
  c.start(s, cmd);
  for (int k = 0; k < 5; ++k) {
    s.t += 0.001;
    c.tick(s, cmd);
  }
  c.setPostureReference(c.homePosture().array() + 0.1);  // a posture error: the last level's QP has work to do
  s.t += 0.001;
  c.tick(s, cmd);
  ASSERT_EQ(c.status(), WholeBodyStatus::kOk);
  const Eigen::VectorXd q_good = cmd.q_ref;
  const int last = c.hqp().numLevels() - 1;
  c.hqp().levelSolver(last).settings().kkt_tol = 1e-30;
  s.t += 0.001;
  c.tick(s, cmd);
  EXPECT_EQ(c.lastQpStatus(), QpStatus::kInaccurate);
  EXPECT_EQ(c.status(), WholeBodyStatus::kSafeQpFailed);
  EXPECT_EQ(c.counters().qp_failures, 1);
  EXPECT_EQ((cmd.q_ref - q_good).norm(), 0.0);
  EXPECT_EQ(cmd.qd_ref.norm(), 0.0);
  c.hqp().levelSolver(last).settings().kkt_tol = centaur::QpSettings().kkt_tol;
  c.resume();
  s.t += 0.001;
  c.tick(s, cmd);
  EXPECT_EQ(c.status(), WholeBodyStatus::kOk);
  EXPECT_EQ(c.lastQpStatus(), QpStatus::kOptimal);
}
