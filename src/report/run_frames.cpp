#include "report/run_frames.hpp"

#include <algorithm>

#include "common/error.hpp"
#include "report/channel_codec.hpp"

namespace centaur::report {

std::vector<Eigen::Index> frameRows(const Eigen::VectorXd& t, double rate_hz) {
  std::vector<Eigen::Index> rows;
  if (t.size() == 0) return rows;
  const double step = 1.0 / rate_hz, eps = 1e-9;
  double next = t[0];
  for (Eigen::Index i = 0; i < t.size(); ++i) {
    if (t[i] + eps < next) continue;
    rows.push_back(i);
    while (next <= t[i] + eps) next += step;
  }
  if (rows.back() != t.size() - 1) rows.push_back(t.size() - 1);
  return rows;
}

namespace {

/// Slot (index in movingBodies()) of each contact body of the log.
void contactSlots(const data::SimLogFile& log, const KinematicModel& model, std::vector<int>& slots,
                  std::vector<double>& radius) {
  const std::vector<int>& moving = model.movingBodies();
  for (const std::string& name : log.header().contact_bodies) {
    const int body = model.bodyId(name);
    const auto it = std::find(moving.begin(), moving.end(), body);
    if (body < 0 || it == moving.end()) {
      throw InputError(log.path(), "contact_bodies",
                       "'" + name + "' is not a body with geoms of the model " + model.path());
    }
    slots.push_back(static_cast<int>(it - moving.begin()));
    radius.push_back(model.contactRadius(body));
  }
}

}  // namespace

nlohmann::json runFrames(const data::SimLogFile& log, KinematicModel& model, double rate_hz) {
  const std::vector<int> addresses = model.jointAddresses(log.header().joint_names, log.path(), "joint_names");
  std::vector<int> slots;
  std::vector<double> radius;
  contactSlots(log, model, slots, radius);
  const Eigen::VectorXd t = log.time();
  const data::RowMatrix q = log.read("q"), base_pos = log.read("base_pos"), base_quat = log.read("base_quat");
  const data::RowMatrix force = log.read("wheel_force");
  const std::vector<Eigen::Index> rows = frameRows(t, rate_hz);

  std::vector<double> times, poses, forces;
  poses.reserve(rows.size() * model.movingBodies().size() * 7);
  for (const Eigen::Index i : rows) {
    times.push_back(t[i]);
    model.bodyPoses(base_pos.row(i).data(), base_quat.row(i).data(), q.row(i).data(), addresses, poses);
    forces.insert(forces.end(), force.row(i).data(), force.row(i).data() + force.cols());
  }
  const std::size_t force_channels = std::max<std::size_t>(1, static_cast<std::size_t>(force.cols()));
  return {{"rate", rate_hz},
          {"frames", rows.size()},
          {"t", encodeFloat32(times)},
          {"pose", encodeInt16Channels(poses, 7 * model.movingBodies().size())},
          {"force", encodeInt16Channels(forces, force_channels)},
          {"force_slots", slots},
          {"force_radius", radius}};
}

}  // namespace centaur::report
