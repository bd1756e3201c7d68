#pragma once
// The robot of a report: its MJCF loaded with MuJoCo used as a kinematics library (never stepped), the bodies
// that carry geoms, and forward kinematics from a logged base pose and joint positions to every moving body's
// world pose. MuJoCo stays private to the report module: only the opaque mjModel pointer appears here.
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

struct mjModel_;
struct mjData_;

namespace centaur::report {

class KinematicModel {
 public:
  /// Loads `mjcf_path` with every geom (visual ones included). InputError naming the file if MuJoCo cannot, or
  /// if the model has no free joint (a floating base is what a report replays).
  explicit KinematicModel(const std::string& mjcf_path);
  ~KinematicModel();
  KinematicModel(const KinematicModel&) = delete;
  KinematicModel& operator=(const KinematicModel&) = delete;

  const std::string& path() const { return path_; }
  const mjModel_* model() const { return model_; }

  /// MuJoCo ids of the bodies that move with the robot and carry at least one geom, in tree order; the
  /// floating base (the free joint's body) first.
  const std::vector<int>& movingBodies() const { return moving_; }
  /// MuJoCo ids of bodies welded to the world that carry geoms (the world body's ground plane, the wall), in
  /// tree order.
  const std::vector<int>& staticBodies() const { return static_; }
  std::string bodyName(int body) const;
  /// Body id by name, -1 if absent.
  int bodyId(const std::string& name) const;

  /// qpos addresses of the joints named `names` (a log's joint order). InputError("<file>: key '<key>': ...")
  /// naming the first name the model lacks or a joint that is not a 1-DoF hinge or slide.
  std::vector<int> jointAddresses(const std::vector<std::string>& names, const std::string& file,
                                  const std::string& key) const;
  /// Effort limit [N m] of each joint in `names` (actuator ctrlrange x gear; +inf when unlimited or unactuated).
  std::vector<double> effortLimits(const std::vector<std::string>& names) const;

  /// Radius [m] of the first colliding geom of `body` (a wheel's tyre), 0 if it has none.
  double contactRadius(int body) const;
  /// Half extents [m] of the first box geom of `body`, zeros if it has none.
  std::vector<double> boxHalfExtents(int body) const;

  /// Puts the front face of body `wall` (if the model has one) at x = wall_x, as the simulator does.
  void placeWall(double wall_x);

  /// World poses of movingBodies() for the base pose (w_p_base, w_quat_base in w, x, y, z) and joint positions
  /// `q` at `addresses`: 7 values per body, position (3) then quaternion w, x, y, z (4), appended to `out`.
  void bodyPoses(const double* w_p_base, const double* w_quat_base, const double* q, const std::vector<int>& addresses,
                 std::vector<double>& out);
  /// World poses of staticBodies() (7 values each, as bodyPoses), e.g. the wall after placeWall().
  std::vector<double> staticPoses();

 private:
  std::string path_;
  mjModel_* model_ = nullptr;
  mjData_* data_ = nullptr;
  int free_qpos_ = -1;
  std::vector<int> moving_, static_;
};

}  // namespace centaur::report
