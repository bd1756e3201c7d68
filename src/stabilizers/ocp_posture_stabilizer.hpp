#pragma once
// Stabilizer 3, the OCP postural task (paper Sec. "OCP Postural Task", eq. posture_oc):
//   tau_{k+1} = tau_k + gamma_tau omega_imu^[P] dt          (phase, wrapped modulo 1: the plan is periodic)
//   q_d = q*_k + M (tau_{k+1} - k / M) (q*_{k+1} - q*_k),   k = floor(M tau_{k+1})
// where q* (M + 1 rows, uniform in tau over one period, row M = row 0) is the arm-flywheel plan
// (`centaur plan arm-flywheel`, planner/arm_flywheel_problem.hpp): its 1 kHz samples (interpolation: samples,
// default) or the OCP knots (interpolation: knots, M = N_s, the paper's form). The paper's per-tick gain is our
// gamma_tau * dt [1/rad]: with dt in the law the replay speed does not depend on the control rate.
// omega_imu^[P] = imu_omega.y() (IMU frame = pelvis frame: pitch rate, > 0 tips the nose down).
// Both arms replay q*: the left arm (j_arm1_*) as planned, the right arm (j_arm2_*) its sagittal mirror image
// (joints 2, 3, 5, 7 change sign), so both produce angular momentum about y of the same sign. Every other joint
// keeps its home value. The IK stack is eq. (box_stack_Raibert) with this posture (postureStackYaml()).
//
// Sign: the phase advances (d tau / dt > 0) for omega_y > 0 when the plan's mean h_y is positive (the OCP
// maximises h_y, so it is); for a plan with negative mean h_y the phase runs backwards instead. Either way a
// positive pitch rate makes the arms spin with h_y > 0 "in the direction of falling" (Raibert's flywheel): the
// reaction on the body is a -y torque that slows the pitch (tests/stabilizers/test_ocp_posture_sign.cpp).
// |d tau / dt| is clamped to max_speed / period, so the joint velocities stay those the plan was bounded with.
//
// Blend: from start(), the arm reference goes smoothly (cubic smoothstep over blend_time) from home to
// q*(tau) (tau = initial_phase while inactive), so the arms are on the trajectory when the jump begins. The phase
// only moves while `active`. When the primitive ends (active true -> false) the arms blend, over blend_time,
// from where they are to `after_end`: home (default: the standing posture the other modes end in), initial
// (q*(tau_0), ready for the next jump) or hold (stay where the phase stopped). If it becomes active again the
// arms blend back onto the trajectory at the held phase.
// update() never allocates and never throws (everything is sized in start()).
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "data/arm_trajectory.hpp"
#include "stabilizers/stabilizer.hpp"

namespace centaur {

class YamlReader;

struct OcpPostureParams {
  std::string flywheel_file;            ///< HDF5 file with group `flywheel_group`; "" = the trajectory is given by
                                        ///< the caller (second constructor)
  std::string flywheel_group = "arm-flywheel";
  double gamma_tau = 1.0;               ///< [1/rad] phase per radian of pitch, [0, 100]
  double max_speed = 1.0;               ///< |d tau/dt| <= max_speed / period: 1 = the planned speed, [0, 10]
  double initial_phase = 0.2;           ///< tau_0 in [0, 1) (0.2: see docs/stabilizers.md, measured)
  double blend_time = 1.0;              ///< [s] home -> q*(tau_0) after start(), [0, 10]
  std::string arms = "both";            ///< both | left | right
  std::string interpolation = "samples";  ///< samples (1 kHz rows) | knots (the OCP nodes, N_s + 1 rows)
  std::string after_end = "home";       ///< home | initial | hold: arm target after the primitive ended
  bool velocity_feedforward = false;    ///< feed d q*/d tau * d tau/dt to the posture task too
  static const char* defaultsYaml();    ///< the `ocp:` section
  void read(YamlReader& r);
};

/// Linear interpolation of eq. (posture_oc) in a periodic table (rows 0..M, uniform in tau, row M = row 0):
/// tau is wrapped into [0, 1). No allocation (out must have table.cols() entries).
void interpolatePeriodic(const data::RowMatrix& table, double tau, Eigen::Ref<Eigen::VectorXd> out) noexcept;

class OcpPostureStabilizer final : public Stabilizer {
 public:
  /// Loads the trajectory from params.flywheel_file; InputError for an empty, missing or invalid file, group or
  /// parameter. This stabilizer never plans: planning on demand belongs to the caller (sim/cli).
  explicit OcpPostureStabilizer(OcpPostureParams params);
  /// With a trajectory already in memory (tests, benchmarks).
  OcpPostureStabilizer(OcpPostureParams params, std::shared_ptr<const data::ArmTrajectory> trajectory);

  const char* name() const override { return "ocp"; }
  std::string stackYaml(const RobotFrames& frames) const override;
  /// Throws InputError if an arm joint of the plan (or its j_arm2_* mirror) is not among joint_names.
  void start(const std::vector<std::string>& joint_names, const Eigen::VectorXd& q_home) override;
  unsigned references() const override;
  void update(const RobotState& state, double dt, bool active, WholeBodyReferences& out) noexcept override;

  /// The part of update() that computes the reference (no controller needed): advances the phase and q_d.
  void step(const RobotState& state, double dt, bool active) noexcept;
  const Eigen::VectorXd& postureReference() const { return q_d_; }
  /// Its velocity feed-forward [rad/s]: the slope of the interpolated segment times d tau/dt (0 while blending).
  const Eigen::VectorXd& postureVelocity() const { return qd_d_; }
  double phase() const { return tau_; }
  /// +1 if the phase advances with omega_y > 0, -1 if it runs backwards (plan with negative mean h_y).
  double direction() const { return direction_; }
  const data::ArmTrajectory& trajectory() const { return *traj_; }
  const OcpPostureParams& params() const { return params_; }

 private:
  void init();
  OcpPostureParams params_;
  std::shared_ptr<const data::ArmTrajectory> traj_;
  data::RowMatrix table_;  // rows uniform in tau, last = first
  double direction_ = 1.0;
  std::vector<int> left_, right_;  // RobotModel joint indices (-1: not driven)
  Eigen::VectorXd q_home_, q_d_, q_arm_, q_from_;
  Eigen::VectorXd qd_d_;  // velocity feed-forward of q_d (n): d q*/d tau * d tau/dt while replaying (lead)  // q_from_: where the current blend started (n)
  Eigen::Matrix<double, 7, 1> mirror_;
  double tau_ = 0.0, elapsed_ = 0.0;  // elapsed_: time since the current blend started
  bool was_active_ = false, ended_ = false;
  enum class AfterEnd { kHome, kInitial, kHold } after_end_ = AfterEnd::kHome;
};

}  // namespace centaur
