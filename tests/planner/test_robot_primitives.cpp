// ctest-labels: physics integration
// Both jumps planned for every shipped robot on its derived template (or, for CENTAURO, its preset), read back
// from the HDF5 file alone: the template's Newton-Euler equations hold at every knot (linear momentum rate =
// contact forces + weight, angular momentum rate about the CoM = the contact forces' moments, both within
// 0.05 % of the weight), and the file names the robot and its description's hash.
#include <gtest/gtest.h>

#include "data/primitive_io.hpp"
#include "model/template_model.hpp"
#include "model/template_params.hpp"
#include "planner/jump_problem.hpp"
#include "robot/robot_registry.hpp"
#include "support/temp_dir.hpp"

using namespace centaur;

namespace {

struct Case {
  std::string robot, primitive;
};

std::vector<Case> cases() {
  std::vector<Case> out;
  for (const auto& r : robot::robotNames()) {
    for (const auto& p : planner::jumpPrimitiveNames()) out.push_back({r, p});
  }
  return out;
}

// The template's parameters as the primitive file records them.
model::TemplateParams fromFile(const data::Primitive& p) {
  model::TemplateParams P;
  P.waist_mass = p.scalars.at("waist_mass");
  P.foot_mass = p.scalars.at("foot_mass");
  P.gravity = p.scalars.at("gravity");
  const auto& c = p.vectors.at("waist_com");
  P.waist_com = Eigen::Vector3d(c[0], c[1], c[2]);
  P.waist_inertia = Eigen::Map<const Eigen::Matrix3d>(p.vectors.at("waist_inertia").data());
  P.foot_inertia = Eigen::Map<const Eigen::Matrix3d>(p.vectors.at("foot_inertia").data());
  const auto& h = p.vectors.at("hip_offsets");
  for (int i = 0; i < 4; ++i) P.hip[i] = Eigen::Vector3d(h[3 * i], h[3 * i + 1], h[3 * i + 2]);
  return P;
}

class RobotPrimitive : public ::testing::TestWithParam<Case> {};

TEST_P(RobotPrimitive, ObeysNewtonEulerFromTheFileAlone) {
  const Case& c = GetParam();
  const planner::JumpConfig cfg = planner::loadJumpConfig(c.primitive, "", {"robot=" + c.robot});
  const planner::JumpProblem problem(cfg);
  centaur_test::TempDir dir{"centaur-robot-primitive"};
  data::writePrimitive(dir.file("p.h5"), problem.toPrimitive(problem.solve(false)));
  const data::Primitive p = data::readPrimitives(dir.file("p.h5")).at(0);
  ASSERT_EQ(p.solve.status, "solved") << c.robot << " " << c.primitive;
  EXPECT_EQ(p.strings.at("robot"), c.robot);
  EXPECT_EQ(p.strings.at("robot_hash"), robot::loadRobot(c.robot).hash);

  const model::TemplateParams P = fromFile(p);
  const double m = P.totalMass(), mg = m * P.gravity, h = p.t[1] - p.t[0];
  EXPECT_NEAR(m, p.scalars.at("total_mass"), 1e-9);
  auto state = [&](Eigen::Index j, model::VectorQ& q, model::VectorV& v) {
    q = p.q.row(j).transpose();
    v = p.nu.row(j).transpose();
  };
  // The plan holds its dynamics at the knots (each interval's acceleration is constant, so between knots the
  // waist's wrench drifts from what the forces give: resampled_max_underactuation_residual). So check each knot
  // from the first three 1 kHz samples of its interval: a one-sided second-order difference of the momenta.
  double worst_newton = 0.0, worst_euler = 0.0;
  int checked = 0;
  for (Eigen::Index k = 0; k + 1 < p.knot_t.size(); ++k) {
    const Eigen::Index j = static_cast<Eigen::Index>(std::ceil(p.knot_t[k] / h - 1e-9));
    if (j + 2 >= p.samples() || p.t[j + 2] >= p.knot_t[k + 1]) continue;
    model::VectorQ q[3];
    model::VectorV v[3];
    for (int i = 0; i < 3; ++i) state(j + i, q[i], v[i]);
    auto rate = [&](auto momentum) {
      return Eigen::Vector3d((-3.0 * momentum(P, q[0], v[0]) + 4.0 * momentum(P, q[1], v[1]) - momentum(P, q[2], v[2])) / (2 * h));
    };
    const Eigen::Vector3d dp = rate(model::linearMomentum), dL = rate(model::angularMomentumAboutCom);
    const Eigen::Vector3d com = model::centerOfMass(P, q[0]);
    Eigen::Vector3d f(0, 0, -mg), tau = Eigen::Vector3d::Zero();
    for (int i = 0; i < 4; ++i) {
      const Eigen::Vector3d F = p.force.row(j).segment<3>(3 * i).transpose();
      const Eigen::Vector3d at = p.foot_pos.row(j).segment<3>(3 * i).transpose();
      f += F;
      tau += (at - com).cross(F);
    }
    worst_newton = std::max(worst_newton, (dp - f).norm() / mg);
    worst_euler = std::max(worst_euler, (dL - tau).norm() / mg);  // per metre of lever
    ++checked;
  }
  EXPECT_GT(checked, p.knot_t.size() / 2);
  EXPECT_LT(worst_newton, 0.0005) << c.robot << " " << c.primitive << ": Newton off by " << 100 * worst_newton << " % of the weight";
  EXPECT_LT(worst_euler, 0.0005) << c.robot << " " << c.primitive << ": Euler off by " << 100 * worst_euler << " % of weight x 1 m";
}

std::string caseName(const ::testing::TestParamInfo<Case>& info) {
  std::string n = info.param.robot + "_" + info.param.primitive;
  for (char& ch : n) ch = std::isalnum(static_cast<unsigned char>(ch)) ? ch : '_';
  return n;
}

INSTANTIATE_TEST_SUITE_P(Robots, RobotPrimitive, ::testing::ValuesIn(cases()), caseName);

}  // namespace
