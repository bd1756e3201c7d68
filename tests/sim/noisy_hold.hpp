#pragma once
// A sensor-driven PD for the sim tests: its command depends on the (possibly noisy) measurements, so any
// difference between runs that should be identical (determinism, cross-talk between parallel runs) shows.
#include "controller/robot_interface.hpp"

namespace centaur::test {

class NoisyHold : public Controller {
 public:
  explicit NoisyHold(double gain = 1.0) : gain_(gain) {}
  void start(const RobotState& s, JointCommand& c) override {
    c.resize(s.q.size());
    tick(s, c);
  }
  void tick(const RobotState& s, JointCommand& c) noexcept override {
    c.q_ref.setConstant(0.1);
    c.qd_ref.setZero();
    c.kp.setConstant(30.0 * gain_);
    c.kd.setConstant(1.0);
    c.tau_ff = -0.2 * s.q + 0.05 * s.imu_omega.x() * Eigen::VectorXd::Ones(s.q.size());
  }

 private:
  double gain_;
};

}  // namespace centaur::test
