// ctest-labels: sim physics
// Motors are matched to their joints by the joint they act on, not by their order in the MJCF: CENTAURO with its
// 39 motors listed in reverse runs bit for bit as the shipped model, with the joints in the model's order.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <vector>

#include "model/robot_model.hpp"
#include "sim/mujoco_robot.hpp"
#include "support/temp_dir.hpp"

using namespace centaur;
using namespace centaur::sim;

namespace {

const std::string kModel = std::string(CENTAUR_SOURCE_DIR) + "/models/centauro/centauro.xml";

// The MJCF text with its <motor .../> lines in reverse order.
std::string reversedMotors(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> lines, motors;
  std::string line;
  std::size_t first = 0;
  while (std::getline(in, line)) {
    if (line.find("<motor ") != std::string::npos) {
      if (motors.empty()) first = lines.size();
      motors.push_back(line);
      continue;
    }
    lines.push_back(line);
  }
  lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(first), motors.rbegin(), motors.rend());
  std::string out;
  for (const auto& l : lines) out += l + "\n";
  return out;
}

// A joint-specific impedance so that a mix-up of motors shows at once.
class DistinctGains : public Controller {
 public:
  void start(const RobotState& s, JointCommand& c) override {
    c.resize(s.q.size());
    tick(s, c);
  }
  void tick(const RobotState& s, JointCommand& c) noexcept override {
    for (Eigen::Index i = 0; i < s.q.size(); ++i) {
      c.q_ref[i] = 0.01 * static_cast<double>(i);
      c.qd_ref[i] = 0.0;
      c.tau_ff[i] = 0.1 * static_cast<double>(i % 5);
      c.kp[i] = 50.0 + 10.0 * static_cast<double>(i);
      c.kd[i] = 1.0;
    }
  }
};

TEST(MotorOrder, ReversedMotorsRunBitForBitWithJointsInModelOrder) {
  centaur_test::TempDir dir{"centaur-motor-order"};
  std::ifstream in(kModel);
  std::stringstream buf;
  buf << in.rdbuf();
  const std::string reversed = dir.file("centauro.xml");
  std::ofstream(reversed) << reversedMotors(buf.str());

  SimSettings a, b;
  a.model_path = kModel;
  b.model_path = reversed;
  MujocoRobot shipped(a), shuffled(b);
  const RobotModel model(kModel);
  EXPECT_EQ(shuffled.jointNames(), model.jointNames());
  EXPECT_EQ(shipped.jointNames(), shuffled.jointNames());
  DistinctGains ca, cb;
  RobotState sa, sb;
  JointCommand ja, jb;
  sa.resize(shipped.numJoints());
  sb.resize(shuffled.numJoints());
  shipped.read(sa);
  shuffled.read(sb);
  ca.start(sa, ja);
  cb.start(sb, jb);
  for (int k = 0; k < 300; ++k) {
    shipped.controlPeriod(ca, sa, ja);
    shuffled.controlPeriod(cb, sb, jb);
  }
  ASSERT_EQ(sa.q.size(), sb.q.size());
  for (Eigen::Index i = 0; i < sa.q.size(); ++i) {
    EXPECT_EQ(sa.q[i], sb.q[i]) << model.jointNames()[static_cast<std::size_t>(i)];
    EXPECT_EQ(sa.tau[i], sb.tau[i]) << model.jointNames()[static_cast<std::size_t>(i)];
  }
  EXPECT_EQ(shipped.basePosition(), shuffled.basePosition());
}

}  // namespace
