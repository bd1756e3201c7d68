// ctest-labels: unit physics
// Contact force distribution on CENTAURO: standing statics (weight carried, moments balanced, friction
// respected), a wheel declared off carries nothing, a feasible consistent F_d is returned exactly, tau_ff is
// the inverse dynamics of the returned forces (checked with an independent Jacobian path of RobotModel),
// infeasible demands are relaxed gracefully, a wall normal, invalid input, and compute() never allocates.
#include <gtest/gtest.h>

#include "support/allocation_counter.hpp"

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>
#include <string>

#include <Eigen/SVD>

#include "common/error.hpp"
#include "common/yaml_reader.hpp"
#include "controller/force_distribution.hpp"

using namespace centaur;
using Eigen::Vector3d;
using Eigen::VectorXd;
using Status = ForceDistributionStatus;

namespace {
const std::string kModel = std::string(CENTAUR_SOURCE_DIR) + "/models/centauro/centauro.xml";
}  // namespace


namespace {

class ForceDistributionTest : public ::testing::Test {
 protected:
  void SetUp() override {
    model_ = std::make_unique<RobotModel>(kModel);
    q_ = VectorXd::Zero(model_->nq());
    q_[2] = 0.71884985;
    q_[3] = 1.0;
    q_.tail(model_->numJoints()) = model_->homeJoints();
    v_ = VectorXd::Zero(model_->nv());
    vdot_ = VectorXd::Zero(model_->nv());
    model_->update(q_, v_);
    fd_.init(*model_, params_);
    weight_ = model_->totalMass() * 9.81;
  }

  // Friction pyramid and unilaterality of every stance wheel (same tangents as the implementation).
  void expectFrictionRespected(const WheelContacts& c, double mu) const {
    for (int k = 0; k < 4; ++k) {
      const Vector3d F = fd_.forces().col(k);
      if (!c.stance[k]) {
        EXPECT_EQ(F.norm(), 0.0) << "wheel " << k + 1;
        continue;
      }
      const Vector3d n = c.normal[k].normalized();
      const Vector3d a = std::abs(n.x()) < 0.9 ? Vector3d::UnitX() : Vector3d::UnitY();
      const Vector3d t1 = (a - a.dot(n) * n).normalized(), t2 = n.cross(t1);
      const double fn = n.dot(F);
      EXPECT_GE(fn, -1e-9) << "wheel " << k + 1;
      EXPECT_LE(std::abs(t1.dot(F)), mu * fn + 1e-7) << "wheel " << k + 1;
      EXPECT_LE(std::abs(t2.dot(F)), mu * fn + 1e-7) << "wheel " << k + 1;
    }
  }

  // Independent inverse dynamics: M vdot + b - sum J^T F on all rows, J from pointJacobian (frame-local
  // point) instead of worldPointJacobian.
  VectorXd inverseDynamics(const VectorXd& vdot) const {
    const int nv = model_->nv();
    RowMatrixXd M(nv, nv), J(3, nv);
    VectorXd b(nv);
    model_->massMatrix(M);
    model_->biasForces(b);
    VectorXd rhs = M * vdot + b;
    for (int k = 0; k < 4; ++k) {
      const int body = model_->frameId("wheel_" + std::to_string(k + 1));
      const Vector3d f_point = model_->framePose(body).inverse() * fd_.contactPoint(k);
      model_->pointJacobian(body, f_point, J);
      rhs -= J.transpose() * fd_.forces().col(k);
    }
    return rhs;
  }

  std::unique_ptr<RobotModel> model_;
  ForceDistributionParams params_;
  ForceDistribution fd_;
  VectorXd q_, v_, vdot_;
  double weight_ = 0.0;
};

TEST_F(ForceDistributionTest, StandingStaticsCarryTheWeightAndBalanceMoments) {
  WheelContacts c;
  ForceDistribution::Forces Fd = ForceDistribution::Forces::Zero();
  Fd.row(2).setConstant(weight_ / 4);  // equal split: inconsistent with the CoM 0.1 m ahead
  ASSERT_EQ(fd_.compute(*model_, vdot_, Fd, c), Status::kOk);
  const auto& F = fd_.forces();
  EXPECT_NEAR(F.row(2).sum(), weight_, 1e-3 * weight_);
  EXPECT_NEAR(F.row(2).sum(), weight_, 1e-6 * weight_);  // in fact exact
  EXPECT_NEAR(F.row(0).sum(), 0.0, 1e-6 * weight_);
  EXPECT_NEAR(F.row(1).sum(), 0.0, 1e-6 * weight_);
  // Moments about the CoM vanish: sum (c_k - com) x F_k = 0 (static, v = 0).
  Vector3d moment = Vector3d::Zero();
  for (int k = 0; k < 4; ++k) moment += (fd_.contactPoint(k) - model_->com()).cross(Vector3d(F.col(k)));
  EXPECT_LT(moment.norm(), 1e-6 * weight_);
  EXPECT_LT(fd_.residual(), 1e-6 * weight_);
  // More load on the front wheels (1, 2): the CoM is ahead of the wheel centre.
  EXPECT_GT(F(2, 0) + F(2, 1), F(2, 2) + F(2, 3));
  for (int k = 0; k < 4; ++k) {
    EXPECT_GT(F(2, k), 0.1 * weight_);
    EXPECT_NEAR(fd_.contactPoint(k).z(), 0.0, 1e-3) << "contact point on the ground";
  }
  expectFrictionRespected(c, params_.friction);
}

TEST_F(ForceDistributionTest, WheelDeclaredOffCarriesNothingAndTheOthersBalance) {
  WheelContacts c;
  c.stance[2] = false;  // rear-left: the CoM stays inside the triangle of wheels 1, 2, 4
  ForceDistribution::Forces Fd = ForceDistribution::Forces::Zero();
  Fd.row(2).setConstant(weight_ / 3);
  ASSERT_EQ(fd_.compute(*model_, vdot_, Fd, c), Status::kOk);
  const auto& F = fd_.forces();
  EXPECT_EQ(F.col(2).norm(), 0.0);
  EXPECT_NEAR(F.row(2).sum(), weight_, 1e-6 * weight_);
  EXPECT_LT(fd_.residual(), 1e-6 * weight_);
  expectFrictionRespected(c, params_.friction);
  // Joint torques of the lifted leg: only its own gravity, no contact force (tau_ff = g on those rows).
  EXPECT_LT((inverseDynamics(vdot_).tail(model_->numJoints()) - fd_.tauFeedforward()).norm(), 1e-8 * weight_);
}

TEST_F(ForceDistributionTest, FeasibleConsistentDesiredForcesAreReturnedExactly) {
  WheelContacts c;
  ASSERT_EQ(fd_.compute(*model_, vdot_, ForceDistribution::Forces::Zero(), c), Status::kOk);
  const ForceDistribution::Forces F0 = fd_.forces();
  // Move along the null space of the floating-base rows (internal forces): still consistent; small enough
  // to stay strictly inside the friction pyramids.
  Eigen::Matrix<double, 6, 12> A;
  for (int k = 0; k < 4; ++k) A.block<6, 3>(0, 3 * k) = fd_.contactJacobian(k).leftCols<6>().transpose();
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullV);
  const Eigen::VectorXd null_dir = svd.matrixV().col(11) + 0.5 * svd.matrixV().col(7);
  ASSERT_LT((A * null_dir).norm(), 1e-9);
  Eigen::Matrix<double, 12, 1> f = Eigen::Map<const Eigen::Matrix<double, 12, 1>>(F0.data());
  f += 20.0 * null_dir.normalized();
  const ForceDistribution::Forces Fd = Eigen::Map<const ForceDistribution::Forces>(f.data());
  ASSERT_GT((Fd - F0).norm(), 19.0);
  ASSERT_EQ(fd_.compute(*model_, vdot_, Fd, c), Status::kOk);
  expectFrictionRespected(c, params_.friction);
  EXPECT_LT((fd_.forces() - Fd).cwiseAbs().maxCoeff(), 1e-5);  // eps = 1e-8 -> ~1e-6 N
}

TEST_F(ForceDistributionTest, TauFeedforwardIsTheInverseDynamicsOfTheReturnedForces) {
  // A moving state and a non-trivial desired acceleration.
  std::srand(7);
  v_ = 0.2 * VectorXd::Random(model_->nv());
  vdot_ = 0.5 * VectorXd::Random(model_->nv());
  q_.tail(model_->numJoints()) += 0.05 * VectorXd::Random(model_->numJoints());
  model_->update(q_, v_);
  WheelContacts c;
  c.stance[1] = false;
  ForceDistribution::Forces Fd = ForceDistribution::Forces::Zero();
  Fd.row(2).setConstant(weight_ / 3);
  const Status s = fd_.compute(*model_, vdot_, Fd, c);
  ASSERT_NE(s, Status::kFailed);
  const VectorXd id = inverseDynamics(vdot_);
  EXPECT_LT((id.tail(model_->numJoints()) - fd_.tauFeedforward()).cwiseAbs().maxCoeff(), 1e-8 * weight_);
  EXPECT_NEAR(id.head<6>().norm(), fd_.residual(), 1e-8 * weight_);
  if (s == Status::kOk) {
    EXPECT_LT(id.head<6>().norm(), 1e-6 * weight_);
  }
  expectFrictionRespected(c, params_.friction);
}

TEST_F(ForceDistributionTest, InfeasibleDemandIsRelaxedWithinFriction) {
  // 10 m/s^2 forward base acceleration with mu = 0.6 cannot be produced by the wheels: the hard problem
  // is infeasible, the relaxed one returns the best forces inside the pyramids.
  vdot_[0] = 10.0;
  WheelContacts c;
  const Status s = fd_.compute(*model_, vdot_, ForceDistribution::Forces::Zero(), c);
  EXPECT_EQ(s, Status::kRelaxed);
  expectFrictionRespected(c, params_.friction);
  const auto& F = fd_.forces();
  // Saturated: the forward push is mu times the load N, and N minimises the weighted residual
  // (mu N - m a)^2 + (N - m g)^2 (moments can still be balanced by the split): N = m (mu a + g) / (1 + mu^2).
  const double mu = params_.friction, m = model_->totalMass();
  EXPECT_NEAR(F.row(0).sum(), mu * F.row(2).sum(), 1e-3 * weight_);
  EXPECT_NEAR(F.row(2).sum(), m * (mu * 10.0 + 9.81) / (1.0 + mu * mu), 0.01 * weight_);
  EXPECT_GT(fd_.residual(), 0.1 * weight_);
  EXPECT_LT((inverseDynamics(vdot_).tail(model_->numJoints()) - fd_.tauFeedforward()).norm(), 1e-8 * weight_);
  // 5 m/s^2 is feasible (0.51 g < mu g): hard rows hold.
  vdot_[0] = 5.0;
  EXPECT_EQ(fd_.compute(*model_, vdot_, ForceDistribution::Forces::Zero(), c), Status::kOk);
  EXPECT_LT(fd_.residual(), 1e-6 * weight_);
  expectFrictionRespected(c, params_.friction);
}

TEST_F(ForceDistributionTest, WallNormalUsesTheWheelSideAsContactPoint) {
  // Wheel 1 (front-left) against a wall ahead of it (surface normal -x): its contact point is the front
  // of the rim, its normal force pushes backwards; wheels 2-4 stay on the ground.
  WheelContacts c;
  c.normal[0] = -Vector3d::UnitX();
  const Status s = fd_.compute(*model_, vdot_, ForceDistribution::Forces::Zero(), c);
  ASSERT_EQ(s, Status::kOk);
  const Eigen::Isometry3d w_T_c = model_->framePose(model_->frameId("wheel_centre_1"));
  EXPECT_NEAR((fd_.contactPoint(0) - w_T_c.translation() - params_.wheel_radius * Vector3d::UnitX()).norm(), 0.0,
              1e-6);
  expectFrictionRespected(c, params_.friction);
  EXPECT_NEAR(fd_.forces().row(2).sum(), weight_, 1e-6 * weight_);
}

TEST_F(ForceDistributionTest, InvalidInputFailsAndKeepsTheLastGoodOutput) {
  WheelContacts c;
  ASSERT_EQ(fd_.compute(*model_, vdot_, ForceDistribution::Forces::Zero(), c), Status::kOk);
  const ForceDistribution::Forces F = fd_.forces();
  const VectorXd tau = fd_.tauFeedforward();
  VectorXd bad = vdot_;
  bad[3] = std::nan("");
  EXPECT_EQ(fd_.compute(*model_, bad, ForceDistribution::Forces::Zero(), c), Status::kFailed);
  c.normal[1].setZero();
  EXPECT_EQ(fd_.compute(*model_, vdot_, ForceDistribution::Forces::Zero(), c), Status::kFailed);
  EXPECT_EQ(fd_.forces(), F);
  EXPECT_EQ(fd_.tauFeedforward(), tau);
  ForceDistribution uninit;
  EXPECT_EQ(uninit.compute(*model_, vdot_, ForceDistribution::Forces::Zero(), WheelContacts{}), Status::kFailed);
  ForceDistributionParams p;
  p.wheel_bodies[2] = "no_such_wheel";
  EXPECT_THROW(uninit.init(*model_, p), InputError);
}

TEST(ForceDistributionParams, DocumentedDefaultsAreTheDefaultsAndRangesAreEnforced) {
  const YAML::Node doc = YAML::Load(ForceDistributionParams::defaultsYaml());
  YamlReader all(doc["force_distribution"], "defaults", "force_distribution");
  ForceDistributionParams q;
  q.friction = 0.1;  // overwritten by the documented default
  q.dynamics_weight = 3.0;
  q.read(all);
  EXPECT_NO_THROW(all.finish());
  const ForceDistributionParams d;
  EXPECT_EQ(q.friction, d.friction);
  EXPECT_EQ(q.wheel_radius, d.wheel_radius);
  EXPECT_EQ(q.min_normal_force, d.min_normal_force);
  EXPECT_EQ(q.max_normal_force, d.max_normal_force);
  EXPECT_EQ(q.tracking_weight, d.tracking_weight);
  EXPECT_EQ(q.regularization, d.regularization);
  EXPECT_EQ(q.dynamics_weight, d.dynamics_weight);
  const YAML::Node bad = YAML::Load("{friction: 7.0}");
  YamlReader rb(bad, "cfg.yaml", "force_distribution");
  ForceDistributionParams b;
  EXPECT_THROW(b.read(rb), InputError);
}

TEST_F(ForceDistributionTest, RegularizationKeepsTheRelaxedQpInTheSolversRange) {
  // The relaxed QP's Hessian is (tracking_weight + regularization) I + dynamics_weight J_u J_u': below
  // tracking_weight + regularization = 1e-7 dynamics_weight it would leave the QP solver's accurate range, so
  // such settings are refused (YAML: file and key named; init(): InputError). At the limit, minimum-norm forces
  // (tracking_weight 0) still give the analytic relaxed answer of InfeasibleDemandIsRelaxedWithinFriction.
  const YAML::Node bad = YAML::Load("{tracking_weight: 0.0, regularization: 1.0e-8, dynamics_weight: 1.0e4}");
  YamlReader rb(bad, "cfg.yaml", "force_distribution");
  ForceDistributionParams b;
  try {
    b.read(rb);
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("cfg.yaml"), std::string::npos) << what;
    EXPECT_NE(what.find("force_distribution.regularization"), std::string::npos) << what;
    EXPECT_NE(what.find("0.001"), std::string::npos) << what;  // the smallest allowed value here
  }
  ForceDistributionParams p;
  p.tracking_weight = 0.0;
  p.regularization = 1e-12;
  p.dynamics_weight = 1e9;
  ForceDistribution other;
  EXPECT_THROW(other.init(*model_, p), InputError);
  p.dynamics_weight = 1e4;
  p.regularization = 1e-3;  // = 1e-7 x dynamics_weight: accepted
  const YAML::Node ok = YAML::Load("{tracking_weight: 0.0, regularization: 1.0e-3, dynamics_weight: 1.0e4}");
  YamlReader ro(ok, "cfg.yaml", "force_distribution");
  EXPECT_NO_THROW(b.read(ro));
  other.init(*model_, p);
  vdot_[0] = 10.0;
  WheelContacts c;
  ASSERT_EQ(other.compute(*model_, vdot_, ForceDistribution::Forces::Zero(), c), Status::kRelaxed);
  const auto& F = other.forces();
  const double mu = p.friction, m = model_->totalMass();
  EXPECT_NEAR(F.row(0).sum(), mu * F.row(2).sum(), 1e-3 * weight_);
  EXPECT_NEAR(F.row(2).sum(), m * (mu * 10.0 + 9.81) / (1.0 + mu * mu), 0.01 * weight_);
}

TEST_F(ForceDistributionTest, ComputeNeverAllocates) {
  WheelContacts c, three;
  three.stance[3] = false;
  ForceDistribution::Forces Fd = ForceDistribution::Forces::Zero();
  Fd.row(2).setConstant(weight_ / 4);
  VectorXd fast = vdot_;
  fast[0] = 10.0;
  Status s[4];
  int counts[3] = {0, 0, 0};
  const long before = centaur_test::heapAllocations();
  for (int i = 0; i < 1000; ++i) {  // 1000 ticks cycling through 4 wheels, 3 wheels, relaxed, 4 wheels
    s[0] = fd_.compute(*model_, vdot_, Fd, c);
    s[1] = fd_.compute(*model_, vdot_, Fd, three);
    s[2] = fd_.compute(*model_, fast, Fd, c);  // hard infeasible -> relaxed QP
    s[3] = fd_.compute(*model_, vdot_, Fd, c);
    for (Status x : s) ++counts[static_cast<int>(x)];
  }
  const long after = centaur_test::heapAllocations();
  EXPECT_EQ(after - before, 0);
  EXPECT_EQ(counts[static_cast<int>(Status::kOk)], 3000);
  EXPECT_EQ(counts[static_cast<int>(Status::kRelaxed)], 1000);
}

}  // namespace
