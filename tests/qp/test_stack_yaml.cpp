// ctest-labels: unit
// YAML form of a stack: the same stack written in YAML and in C++ gives the same solution; task types come
// from a registry the test fills (as the robot code will); bad input names the file and key.
#include <gtest/gtest.h>

#include "qp/hqp_solver.hpp"
#include "qp/stack_yaml.hpp"
#include "toy_arm.hpp"

using namespace centaur;
using centaur::test::PlanarArm;
using centaur::test::PostureTask;
using centaur::test::TipPositionTask;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

// The registry a toy "robot" provides: types capture the arm (by reference) and the tick.
TaskRegistry toyRegistry(const PlanarArm& arm, double dt, const VectorXd& q_min, const VectorXd& q_max,
                         const VectorXd& qd_max) {
  TaskRegistry reg;
  reg.addTask("TipPosition", [&arm](const std::string& name, YamlReader& r) -> TaskPtr {
    auto t = std::make_shared<TipPositionTask>(name, arm);
    r.get("target", t->target, -10.0, 10.0);
    return t;
  });
  reg.addTask("Postural", [&arm](const std::string& name, YamlReader& r) -> TaskPtr {
    auto t = std::make_shared<PostureTask>(name, arm);
    t->q_ref = arm.q;
    if (r.has("reference")) r.get("reference", t->q_ref, -10.0, 10.0);
    return t;
  });
  reg.addTask("Linear", [n = arm.dof()](const std::string& name, YamlReader& r) -> TaskPtr {
    std::vector<double> a, b;
    r.get("A", a, -1e6, 1e6);
    r.get("b", b, -1e6, 1e6);
    if (b.empty() || a.size() != b.size() * static_cast<std::size_t>(n))
      r.fail("A", "expected rows(b) x " + std::to_string(n) + " numbers, row by row");
    MatrixXd A = Eigen::Map<const Eigen::Matrix<double, -1, -1, Eigen::RowMajor>>(a.data(), b.size(), n);
    return std::make_shared<LinearTask>(name, A, Eigen::Map<const VectorXd>(b.data(), b.size()));
  });
  reg.addConstraint("JointPositionLimits", [&arm, dt, q_min, q_max](const std::string& name, YamlReader& r) {
    double scaling = 1.0;
    r.get("scaling", scaling, 1e-3, 1.0);
    auto c = std::make_shared<JointPositionLimits>(name, arm.dof(), 0, q_min, q_max, dt, scaling);
    c->setJointPositions(arm.q);
    return ConstraintPtr(c);
  });
  reg.addConstraint("JointVelocityLimits", [&arm, qd_max](const std::string& name, YamlReader&) {
    return ConstraintPtr(std::make_shared<JointVelocityLimits>(name, arm.dof(), 0, qd_max));
  });
  return reg;
}

const char* kStackYaml = R"(
stack:
  - [tip]
  - [side, posture]
constraints: [joint_limits, velocity_limits]
regularisation: 1.0e-6
tip:
  type: TipPosition
  target: [0.2, 0.6]
  lambda: 10.0
side:
  type: Linear
  A: [1, 0, 0, 0,
      0, 1, 0, 0,
      0, 0, 1, -1]
  b: [0.5, 0.0, 0.3]
  indices: [0, 2]
  weight: [2.0, 1.0, 3.0]
posture:
  type: Postural
  lambda: 2.0
  weight: 0.1
joint_limits:
  type: JointPositionLimits
  scaling: 0.5
velocity_limits:
  type: JointVelocityLimits
)";

}  // namespace

TEST(StackYaml, YamlAndCppFormsGiveTheSameSolution) {
  PlanarArm arm(4);
  arm.q << 0.4, 0.3, -0.2, 0.5;
  const double dt = 1e-3;
  const VectorXd q_min = VectorXd::Constant(4, -1.0), q_max = VectorXd::Constant(4, 1.0);
  const VectorXd qd_max = VectorXd::Constant(4, 0.8);
  const TaskRegistry reg = toyRegistry(arm, dt, q_min, q_max, qd_max);
  LoadedStack loaded = loadStack(YAML::Load(kStackYaml), "stack.yaml", reg);
  ASSERT_EQ(loaded.stack.levels.size(), 2u);
  EXPECT_EQ(loaded.stack.levels[1].terms[0].rows, (Rows{0, 2}));

  // The same stack in C++.
  auto tip = std::make_shared<TipPositionTask>("tip", arm);
  tip->target = Eigen::Vector2d(0.2, 0.6);
  tip->setLambda(10.0);
  MatrixXd A(3, 4);
  A << 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, -1;
  auto side = std::make_shared<LinearTask>("side", A, Eigen::Vector3d(0.5, 0.0, 0.3));
  side->setWeightDiagonal(Eigen::Vector3d(2.0, 1.0, 3.0));
  auto posture = std::make_shared<PostureTask>("posture", arm);
  posture->q_ref = arm.q;
  posture->setLambda(2.0);
  posture->setWeight(0.1);
  auto lim = std::make_shared<JointPositionLimits>("joint_limits", 4, 0, q_min, q_max, dt, 0.5);
  auto vel = std::make_shared<JointVelocityLimits>("velocity_limits", 4, 0, qd_max);
  const Stack cpp = tip / (side % Rows{0, 2} + posture) << lim << vel;

  HqpSolver from_yaml(loaded.stack, 4), from_cpp(cpp, 4);
  auto yaml_lim = std::static_pointer_cast<JointPositionLimits>(loaded.constraints.at("joint_limits"));
  VectorXd x_yaml(4), x_cpp(4);
  for (int k = 0; k < 300; ++k) {  // closed loop: both follow the same trajectory
    yaml_lim->setJointPositions(arm.q);
    lim->setJointPositions(arm.q);
    from_yaml.update();
    from_cpp.update();
    ASSERT_EQ(from_yaml.solve(x_yaml), QpStatus::kOptimal);
    ASSERT_EQ(from_cpp.solve(x_cpp), QpStatus::kOptimal);
    ASSERT_LT((x_yaml - x_cpp).cwiseAbs().maxCoeff(), 1e-12) << "tick " << k;
    arm.q += dt * x_cpp;
  }
  EXPECT_GT(x_cpp.norm(), 0.0);
  // The velocity limits were binding at the start (the tip gain asks for more than 0.8 rad/s).
  EXPECT_LE(x_cpp.cwiseAbs().maxCoeff(), 0.8);
}

TEST(StackYaml, BadInputNamesFileAndKey) {
  PlanarArm arm(4);
  const VectorXd lo = VectorXd::Constant(4, -1.0), hi = VectorXd::Constant(4, 1.0);
  const TaskRegistry reg = toyRegistry(arm, 1e-3, lo, hi, hi);
  auto expectError = [&](const std::string& yaml, const std::string& needle) {
    try {
      (void)loadStack(YAML::Load(yaml), "bad.yaml", reg);
      ADD_FAILURE() << "no error for:\n" << yaml;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("bad.yaml"), std::string::npos) << e.what();
    }
  };
  expectError("stack: [[tip]]\n", "tip");                                             // no definition
  expectError("stack: [[tip]]\ntip: {type: Nope}\n", "TipPosition");                  // unknown type lists types
  expectError("stack: [[tip]]\ntip: {type: TipPosition, gain: 3}\n", "tip.gain");     // unknown key
  expectError("stack: [[tip]]\ntip: {type: TipPosition, indices: [2]}\n", "indices");  // row out of range
  expectError("stack: [[tip]]\ntip: {type: TipPosition, lambda: -1}\n", "tip.lambda");
  expectError("stack: [[tip]]\ntip: {type: TipPosition, weight: [1, 2, 3]}\n", "tip.weight");
  expectError("stack: [[tip]]\ntip: {type: TipPosition}\nextra: 1\n", "extra");        // unused top-level key
  expectError("stack: [[tip]]\nconstraints: [lim]\ntip: {type: TipPosition}\n", "lim");
  expectError("stack: []\n", "stack");
  // The regularisation must dominate the weights enough for the QP solver (1e-7 x the largest scale x weight).
  expectError("stack: [[tip]]\nregularisation: 1.0e-10\ntip: {type: TipPosition}\n", "regularisation");
  expectError("stack: [[tip]]\ntip: {type: TipPosition, weight: [1.0e3, 1.0]}\n", "regularisation");
  expectError("stack: [[tip]]\ntip: {type: TipPosition, scale: 20.0}\n", "'tip': 20");
  EXPECT_NO_THROW((void)loadStack(YAML::Load("stack: [[tip]]\nregularisation: 1.0e-7\ntip: {type: TipPosition}\n"),
                                  "ok.yaml", reg));
  EXPECT_NO_THROW((void)loadStack(
      YAML::Load("stack: [[tip]]\nregularisation: 1.0e-4\ntip: {type: TipPosition, weight: [1.0e3, 1.0]}\n"),
      "ok.yaml", reg));
}

TEST(StackYaml, RegistryRejectsDuplicateTypes) {
  TaskRegistry reg;
  reg.addTask("T", [](const std::string&, YamlReader&) -> TaskPtr { return nullptr; });
  EXPECT_THROW(reg.addTask("T", [](const std::string&, YamlReader&) -> TaskPtr { return nullptr; }),
               std::invalid_argument);
  EXPECT_TRUE(reg.hasTask("T"));
  EXPECT_FALSE(reg.hasConstraint("T"));
}
