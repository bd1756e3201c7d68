// ctest-labels: unit physics
// Contact detector (generalized-momentum observer + per-leg force + hysteresis) on CENTAURO without a
// simulator: static stance with known wheel forces (estimated exactly from the first sample), the analytic
// first-order step response of the discrete observer and the debounced lift-off/touchdown instants, a
// moving free-floating robot integrated here with RobotModel's dynamics under a known external wheel force
// (the C'v term matters), invalid input, and update() never allocates.
#include <gtest/gtest.h>

#include "support/allocation_counter.hpp"

#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <new>
#include <string>

#include <Eigen/Cholesky>

#include "controller/contact_detector.hpp"
#include "common/error.hpp"
#include "common/yaml_reader.hpp"
#include "controller/force_distribution.hpp"

using namespace centaur;
using Eigen::Vector3d;
using Eigen::VectorXd;

namespace {
const std::string kModel = std::string(CENTAUR_SOURCE_DIR) + "/models/centauro/centauro.xml";
}  // namespace


namespace {

class ContactDetectorTest : public ::testing::Test {
 protected:
  void SetUp() override {
    model_ = std::make_unique<RobotModel>(kModel);
    n_ = model_->numJoints();
    q_ = VectorXd::Zero(model_->nq());
    q_[2] = 0.71884985;
    q_[3] = 1.0;
    q_.tail(n_) = model_->homeJoints();
    v_ = VectorXd::Zero(model_->nv());
    model_->update(q_, v_);
    weight_ = model_->totalMass() * 9.81;
    // Static joint torques that hold the robot on the forces of a consistent distribution.
    ForceDistribution fd;
    fd.init(*model_);
    const VectorXd zero = VectorXd::Zero(model_->nv());
    EXPECT_EQ(fd.compute(*model_, zero, ForceDistribution::Forces::Zero(), WheelContacts{}),
              ForceDistributionStatus::kOk);
    F_stand_ = fd.forces();
    tau_stand_ = fd.tauFeedforward();
    for (int k = 0; k < 4; ++k) J_[k] = fd.contactJacobian(k);
    det_.init(*model_, params_);
  }

  std::unique_ptr<RobotModel> model_;
  int n_ = 0;
  VectorXd q_, v_, tau_stand_;
  ForceDistribution::Forces F_stand_;
  RowMatrixXd J_[4];
  double weight_ = 0.0;
  ContactDetectorParams params_;
  ContactDetector det_;
};

TEST_F(ContactDetectorTest, StaticStanceForcesAreEstimatedFromTheFirstSample) {
  ASSERT_TRUE(det_.update(*model_, tau_stand_, 0.001));
  for (int k = 0; k < 4; ++k) {
    EXPECT_LT((det_.forces().col(k) - F_stand_.col(k)).norm(), 1e-6 * weight_) << "wheel " << k + 1;
    EXPECT_TRUE(det_.inContact(k));
  }
  for (int i = 0; i < 50; ++i) ASSERT_TRUE(det_.update(*model_, tau_stand_, 0.001));
  for (int k = 0; k < 4; ++k) {
    EXPECT_LT((det_.forces().col(k) - F_stand_.col(k)).norm(), 1e-6 * weight_) << "wheel " << k + 1;
    EXPECT_NEAR(det_.normalForce(k), F_stand_(2, k), 1e-6 * weight_);
    EXPECT_TRUE(det_.inContact(k));
  }
}

TEST_F(ContactDetectorTest, StepResponseIsFirstOrderAndHysteresisDebounces) {
  const double dt = 0.001, a = 1.0 - params_.observer_gain * dt;  // discrete pole
  ASSERT_TRUE(det_.update(*model_, tau_stand_, dt));
  // Wheel 3's force vanishes (its leg now carries only itself): tau_leg3 = g_leg3.
  VectorXd tau_lift = tau_stand_;
  tau_lift.noalias() += J_[2].rightCols(n_).transpose() * F_stand_.col(2);
  const double f0 = F_stand_(2, 2);
  int lift_tick = -1;
  for (int i = 1; i <= 30; ++i) {
    ASSERT_TRUE(det_.update(*model_, tau_lift, dt));
    const double expected = f0 * std::pow(a, i);  // r_i = tau_ext + a^i (r_0 - tau_ext)
    EXPECT_NEAR(det_.normalForce(2), expected, 1e-6 * weight_) << "tick " << i;
    EXPECT_NEAR(det_.normalForce(0), F_stand_(2, 0), 1e-6 * weight_);
    if (lift_tick < 0 && !det_.inContact(2)) lift_tick = i;
  }
  // Below off_threshold first at i1 = ceil(ln(off/f0) / ln a); declared off_debounce - 1 ticks later.
  const int i1 = static_cast<int>(std::ceil(std::log(params_.off_threshold / f0) / std::log(a)));
  EXPECT_EQ(lift_tick, i1 + params_.off_debounce - 1);
  EXPECT_LE(lift_tick, 5);  // within 5 ms at 1 kHz
  EXPECT_TRUE(det_.inContact(0) && det_.inContact(1) && det_.inContact(3));
  // Touchdown: back to the stance torques.
  int land_tick = -1;
  for (int i = 1; i <= 30; ++i) {
    ASSERT_TRUE(det_.update(*model_, tau_stand_, dt));
    if (land_tick < 0 && det_.inContact(2)) land_tick = i;
  }
  const double f30 = f0 * std::pow(a, 30);
  const int j1 = static_cast<int>(
      std::ceil(std::log((f0 - params_.on_threshold) / (f0 - f30)) / std::log(a)));
  EXPECT_EQ(land_tick, j1 + params_.on_debounce - 1);
  EXPECT_LE(land_tick, 5);
  // A single sample under the threshold (a spike) does not switch with off_debounce = 2.
  ContactDetector d2;
  ContactDetectorParams p2;
  p2.observer_gain = 1000.0;  // deadbeat: r follows tau_ext in one tick
  d2.init(*model_, p2);
  ASSERT_TRUE(d2.update(*model_, tau_stand_, dt));
  ASSERT_TRUE(d2.update(*model_, tau_lift, dt));
  EXPECT_NEAR(d2.normalForce(2), 0.0, 1e-6 * weight_);
  EXPECT_TRUE(d2.inContact(2));
  ASSERT_TRUE(d2.update(*model_, tau_stand_, dt));
  EXPECT_TRUE(d2.inContact(2));
  ASSERT_TRUE(d2.update(*model_, tau_lift, dt));
  ASSERT_TRUE(d2.update(*model_, tau_lift, dt));
  EXPECT_FALSE(d2.inContact(2));
}

TEST_F(ContactDetectorTest, MovingFreeFloatingRobotUnderAKnownWheelForce) {
  // Integrate M vdot + b = S' tau + J_3' F (semi-implicit Euler, 0.1 ms) with swinging joints (PD-tracked
  // sinusoids, ~1 rad/s) and a
  // constant external force on wheel 3's contact point; the observer (1 kHz) must recover F there and
  // nothing at the other wheels, although the robot moves (p = M v changes, C'v != 0).
  const int nv = model_->nv();
  const Vector3d F_ext(20.0, -15.0, 150.0);
  q_[2] = 1.5;
  v_.setZero();
  v_.segment<3>(3) << 0.3, -0.2, 0.4;  // tumbling base
  RowMatrixXd M(nv, nv), J(3, nv);
  VectorXd b(nv), tau(n_), rhs(nv);
  const int body3 = model_->frameId("wheel_3"), centre3 = model_->frameId("wheel_centre_3");
  const double h = 1e-4;
  det_.reset({false, false, false, false}, false);  // in the air: r_0 = 0, no contact
  const VectorXd home = model_->homeJoints();
  double max_err = 0.0, max_other = 0.0;
  for (int step = 0; step <= 3000; ++step) {
    const double t = step * h;
    model_->update(q_, v_);
    for (int j = 0; j < n_; ++j) {  // joints track home + 0.3 sin(4 t + 0.7 j) with a stiff PD
      const double q_ref = home[j] + 0.3 * std::sin(4.0 * t + 0.7 * j);
      const double qd_ref = 1.2 * std::cos(4.0 * t + 0.7 * j);
      tau[j] = 300.0 * (q_ref - q_[7 + j]) + 10.0 * (qd_ref - v_[6 + j]);
    }
    if (step % 10 == 0) {
      ASSERT_TRUE(det_.update(*model_, tau, 10 * h));
      if (t > 0.05) {  // after ~25 observer time constants
        max_err = std::max(max_err, (det_.forces().col(2) - F_ext).norm());
        for (int k : {0, 1, 3}) max_other = std::max(max_other, det_.forces().col(k).norm());
      }
    }
    model_->massMatrix(M);
    model_->biasForces(b);
    const Vector3d c3 = wheelContactPoint(model_->framePose(centre3), 0.078, Vector3d::UnitZ());
    model_->worldPointJacobian(body3, c3, J);
    rhs = -b;
    rhs.tail(n_) += tau;
    rhs += J.transpose() * F_ext;
    const VectorXd vdot = M.llt().solve(rhs);
    v_ += h * vdot;
    // positions: base (world linear velocity, body angular velocity), joints
    q_.head<3>() += h * v_.head<3>();
    Eigen::Quaterniond quat(q_[3], q_[4], q_[5], q_[6]);
    const Vector3d dth = h * v_.segment<3>(3);
    quat = (quat * Eigen::Quaterniond(Eigen::AngleAxisd(dth.norm(), dth.normalized()))).normalized();
    q_[3] = quat.w();
    q_[4] = quat.x();
    q_[5] = quat.y();
    q_[6] = quat.z();
    q_.tail(n_) += h * v_.tail(n_);
  }
  EXPECT_GT(v_.tail(n_).norm(), 1.0) << "the joints really moved";
  std::printf("max error at wheel 3 %.3f N, max force elsewhere %.3f N\n", max_err, max_other);
  // The observer sees the 1 kHz-sampled motion: errors of a few percent of |F| at most.
  EXPECT_LT(max_err, 0.05 * F_ext.norm());
  EXPECT_LT(max_other, 0.05 * F_ext.norm());
  EXPECT_TRUE(det_.inContact(2));
  EXPECT_FALSE(det_.inContact(0) || det_.inContact(1) || det_.inContact(3));
}

TEST(ContactDetectorParams, DocumentedDefaultsAreTheDefaultsAndRangesAreEnforced) {
  const YAML::Node doc = YAML::Load(ContactDetectorParams::defaultsYaml());
  YamlReader all(doc["contact_detector"], "defaults", "contact_detector");
  ContactDetectorParams q;
  q.observer_gain = 1.0;
  q.on_debounce = 7;
  q.read(all);
  EXPECT_NO_THROW(all.finish());
  const ContactDetectorParams d;
  EXPECT_EQ(q.observer_gain, d.observer_gain);
  EXPECT_EQ(q.on_threshold, d.on_threshold);
  EXPECT_EQ(q.off_threshold, d.off_threshold);
  EXPECT_EQ(q.on_debounce, d.on_debounce);
  EXPECT_EQ(q.off_debounce, d.off_debounce);
  EXPECT_EQ(q.wheel_radius, d.wheel_radius);
  const YAML::Node bad = YAML::Load("{off_threshold: 80.0, on_threshold: 60.0}");  // on must exceed off
  YamlReader rb(bad, "cfg.yaml", "contact_detector");
  ContactDetectorParams b;
  EXPECT_THROW(b.read(rb), InputError);
}

TEST_F(ContactDetectorTest, InvalidInputIsIgnoredAndUpdateNeverAllocates) {
  ASSERT_TRUE(det_.update(*model_, tau_stand_, 0.001));
  VectorXd bad = tau_stand_;
  bad[5] = std::nan("");
  EXPECT_FALSE(det_.update(*model_, bad, 0.001));
  EXPECT_FALSE(det_.update(*model_, tau_stand_, 0.0));
  EXPECT_FALSE(det_.update(*model_, tau_stand_.head(3), 0.001));
  ContactDetector uninit;
  EXPECT_FALSE(uninit.update(*model_, tau_stand_, 0.001));
  ContactDetectorParams p;
  p.leg_joints[1][2] = "no_such_joint";
  EXPECT_THROW(uninit.init(*model_, p), InputError);
  p = ContactDetectorParams();
  p.on_threshold = 10.0;  // below off
  EXPECT_THROW(uninit.init(*model_, p), InputError);

  VectorXd tau_lift = tau_stand_;
  tau_lift.noalias() += J_[0].rightCols(n_).transpose() * F_stand_.col(0);
  bool ok = true;
  const long before = centaur_test::heapAllocations();
  for (int i = 0; i < 1000; ++i) {  // 1000 ticks, wheel 1 lifting and landing every 10
    ok = det_.update(*model_, (i / 10) % 2 == 0 ? tau_lift : tau_stand_, 0.001) && ok;
  }
  const long after = centaur_test::heapAllocations();
  EXPECT_TRUE(ok);
  EXPECT_EQ(after - before, 0);
}

}  // namespace
