#pragma once
// The robot task and constraint types of the YAML stack form (qp/stack_yaml.hpp), on a RobotModel.
// Decision variable of every type: x = v (nv = 6 + n: base twist [w_v_base, b_omega_base] + joint velocities),
// velocity-level IK (the controller integrates q_ref += qd dt). Types and their own keys:
//
//   Cartesian              base_link (frame or "world", default pelvis), distal_link (required),
//                          orientation (bool, default false: 3 position rows; true: + 3 orientation rows)
//                          default lambda 1.0 [1/s]
//   PelvisAngularVelocity  base_link (default pelvis); default lambda 1 (A x = omega_d)
//   Postural               joints (list of joint names, default all); default lambda 1.0 [1/s]
//   AngularMomentum        (no own keys); default lambda 1 (A x = h_ang,d)
//   Com                    (no own keys); default lambda 1.0 [1/s]
//   JointPositionLimits    scaling (0, 1] (default 1): bounds reach the limit in one tick at most
//   JointVelocityLimits    scaling (0, 1] (default 1): |qd| <= scaling qd_max
// The makers capture `model` by reference: it must outlive the tasks.
#include "model/robot_model.hpp"
#include "qp/stack_yaml.hpp"

namespace centaur {

/// Registers the types above; dt [s] is the IK period used by JointPositionLimits.
void registerRobotTasks(TaskRegistry& registry, const RobotModel& model, double dt = 0.001);

}  // namespace centaur
