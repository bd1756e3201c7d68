#pragma once
// Whole-robot kinematics and dynamics for the controller (floating base + actuated joints), read from an
// MJCF file. Implemented on MuJoCo's kinematics/dynamics functions with a PRIVATE data buffer: it never
// reads a simulator's state, only the configuration the controller gives it. No MuJoCo type appears here.
//
// Conventions (documented, they cross the library boundary):
//   generalized coordinates  q = [w_p_base (3), w_quat_base (4: w, x, y, z), joints (n)]   size nq = 7 + n
//   generalized velocities   v = [w_v_base (3, world frame), b_omega_base (3, BASE frame), joints qd (n)]
//                            (MuJoCo's free-joint convention)                                 size nv = 6 + n
//   Frame Jacobians are world-aligned at the frame origin: rows 0-2 linear velocity in W, rows 3-5 angular in W.
//   Centroidal momentum h = A(q) v = [linear (3, W), angular about the CoM (3, W)].
//   Bias forces b(q, v) = C(q, v) v + g(q), with M(q) vdot + b = S^T tau + sum J_c^T f_c.
// Model/Data split: loadRobotModel() parses the MJCF once into a const RobotModelDescription; each RobotModel is a
// workspace on it. Construction allocates everything; update() and all queries never allocate.
#include <Eigen/Core>
#include <Eigen/Geometry>

#include <memory>
#include <string>
#include <vector>

namespace centaur {

using RowMatrixXd = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

struct JointLimits {
  Eigen::VectorXd q_min, q_max;  ///< [rad] (+-inf for continuous joints)
  Eigen::VectorXd qd_max;        ///< [rad/s]
  Eigen::VectorXd tau_max;       ///< [Nm]
};

/// The const part of a robot model: the MJCF parsed once, its joints, frames, limits and home posture. Shared
/// by every RobotModel built from it (a workspace each), read-only after loading: safe to share across threads.
struct RobotModelDescription;

/// Loads the MJCF once; throws InputError naming the file if it cannot be loaded or has no free joint.
std::shared_ptr<const RobotModelDescription> loadRobotModel(const std::string& mjcf_path);

class RobotModel {
 public:
  /// Loads the MJCF (loadRobotModel) for this model alone.
  explicit RobotModel(const std::string& mjcf_path);
  /// A workspace on a shared description: allocates its own data, parses nothing.
  explicit RobotModel(std::shared_ptr<const RobotModelDescription> description);
  ~RobotModel();
  RobotModel(const RobotModel&) = delete;
  RobotModel& operator=(const RobotModel&) = delete;

  // ---- description (const) ----
  /// What this workspace was built on (to build another one on the same description).
  const std::shared_ptr<const RobotModelDescription>& description() const;
  const std::string& path() const;  ///< the MJCF file it was loaded from
  int nq() const;  ///< 7 + n
  int nv() const;  ///< 6 + n
  int numJoints() const;  ///< n, actuated joints
  const std::vector<std::string>& jointNames() const;
  int jointIndex(const std::string& name) const;  ///< -1 if unknown
  const JointLimits& limits() const;
  double totalMass() const;
  /// Frames are bodies or sites of the MJCF, by name; returns -1 if unknown.
  int frameId(const std::string& name) const;
  /// The "home" keyframe's joint positions (n), if the MJCF has one (else zeros).
  Eigen::VectorXd homeJoints() const;

  // ---- state ----
  /// How much update() computes.
  enum class Detail {
    kFull,      ///< everything below
    kMomentum,  ///< kinematics, frame poses and Jacobians, CoM, centroidal momentum matrix A, h = A v (so the CoM
                ///< velocity), Jcom, gravity vector g; NOT the frame velocities, the mass matrix, the bias forces
                ///< nor the momentum bias (their queries return the values of the last update that computed
                ///< them). Enough for a velocity-level IK with a CoM or momentum task and for the base estimator
                ///< in flight, and about half the cost.
    kDynamics,  ///< kinematics, frame poses, velocities and Jacobians, CoM position, mass matrix and bias forces;
                ///< NOT the centroidal momentum matrix, Jcom, h, CoM velocity, gravity vector g nor the Jdot v
                ///< and momentum-bias data (last values of an update that computed them). What force
                ///< distribution and contact detection use.
    kKinematics,  ///< kinematics, frame poses, velocities and Jacobians, CoM position only. What the base
                  ///< estimator in stance uses.
    kJacobians,   ///< kinematics, frame poses and Jacobians, CoM position only (no velocities): what a
                  ///< velocity-level IK without CoM or momentum task uses.
  };
  /// Set q (nq) and v (nv) and compute kinematics, CoM, mass matrix and bias forces. No allocation.
  void update(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Ref<const Eigen::VectorXd>& v,
              Detail detail = Detail::kFull);

  /// Move the floating base by dp (W) and add dv (W) to its linear velocity without recomputing: afterwards
  /// every query returns what it would after update() with those q, v and the same detail (to rounding,
  /// ~1e-13; test against a full update). About 0.5 us instead of a new update: the base estimator
  /// updates the controller's model at its prediction and shifts it to its estimate. No allocation.
  void shiftBase(const Eigen::Vector3d& dp, const Eigen::Vector3d& dv) noexcept;

  // ---- queries on the last update(); none allocates (outputs must be pre-sized) ----
  Eigen::Isometry3d framePose(int frame) const;  ///< w_T_frame
  void frameJacobian(int frame, Eigen::Ref<RowMatrixXd> J) const;  ///< 6 x nv, world-aligned at the frame origin
  /// Jacobian of a point given in frame coordinates (3 x nv), e.g. a wheel contact point.
  void pointJacobian(int frame, const Eigen::Vector3d& f_point, Eigen::Ref<RowMatrixXd> J) const;
  Eigen::Vector3d com() const;                               ///< w_p_com
  void comJacobian(Eigen::Ref<RowMatrixXd> J) const;          ///< 3 x nv
  void centroidalMomentumMatrix(Eigen::Ref<RowMatrixXd> A) const;  ///< 6 x nv
  void massMatrix(Eigen::Ref<RowMatrixXd> M) const;           ///< nv x nv
  void biasForces(Eigen::Ref<Eigen::VectorXd> b) const;       ///< nv: C v + g
  void gravityForces(Eigen::Ref<Eigen::VectorXd> g) const;    ///< nv: g(q)

  // ---- additions (same conventions; computed on the last update(), no allocation) ----
  using Vector6d = Eigen::Matrix<double, 6, 1>;
  /// Number of frames (bodies, then sites); frame ids are 0 .. numFrames()-1.
  int numFrames() const;
  const std::string& frameName(int frame) const;
  /// Frame velocity J v: [linear velocity of the frame origin (W); angular velocity (W)].
  Vector6d frameVelocity(int frame) const;
  /// Frame bias acceleration Jdot v (the frame's acceleration when vdot = 0): [classical linear
  /// acceleration of the origin (W); angular (W)]. Exact (from MuJoCo's cdof_dot), no gravity.
  Vector6d frameBiasAcceleration(int frame) const;
  /// Jdot v of a point given in frame coordinates (3, W), e.g. a wheel contact point.
  Eigen::Vector3d pointBiasAcceleration(int frame, const Eigen::Vector3d& f_point) const;
  /// Jacobian (3 x nv) of the material point of the frame's body that is at WORLD position w_point now,
  /// e.g. the wheel's point in contact with the ground (rolling: its velocity is zero).
  void worldPointJacobian(int frame, const Eigen::Vector3d& w_point, Eigen::Ref<RowMatrixXd> J) const;
  /// Jdot v of that material point (3, W).
  Eigen::Vector3d worldPointBiasAcceleration(int frame, const Eigen::Vector3d& w_point) const;
  Eigen::Vector3d comVelocity() const;          ///< J_com v (W)
  Eigen::Vector3d comBiasAcceleration() const;  ///< Jdot_com v (W)
  /// Centroidal momentum h = A v: [linear (W); angular about the CoM (W)].
  Vector6d centroidalMomentum() const;
  /// Centroidal momentum bias Adot v (so that hdot = A vdot + Adot v), same layout as h.
  Vector6d centroidalMomentumBias() const;
  Eigen::Vector3d gravity() const;  ///< [m/s^2] the model's gravity vector (W)
  /// The configuration used by the last update() (nq) and velocity (nv).
  const Eigen::VectorXd& q() const;
  const Eigen::VectorXd& v() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace centaur
