#include "controller/task_postural.hpp"

#include <numeric>
#include <stdexcept>

namespace centaur {

namespace {
std::vector<int> allIfEmpty(std::vector<int> j, int n) {
  if (j.empty()) {
    j.resize(static_cast<std::size_t>(n));
    std::iota(j.begin(), j.end(), 0);
  }
  return j;
}
}  // namespace

PosturalTask::PosturalTask(std::string name, const RobotModel& model, std::vector<int> joints)
    : Task(std::move(name), static_cast<int>(allIfEmpty(joints, model.numJoints()).size()), model.nv()),
      model_(model),
      joints_(allIfEmpty(std::move(joints), model.numJoints())) {
  for (int j : joints_) {
    if (j < 0 || j >= model.numJoints()) throw std::invalid_argument("Postural task '" + name_ + "': bad joint index");
  }
  for (int r = 0; r < rows(); ++r) A_(r, 6 + joints_[static_cast<std::size_t>(r)]) = 1.0;
  q_d_ = model.homeJoints();
  qd_ff_.setZero(model.numJoints());
}

void PosturalTask::update() {
  const auto q = model_.q().tail(model_.numJoints());
  for (int r = 0; r < rows(); ++r) {
    const int j = joints_[static_cast<std::size_t>(r)];
    b_[r] = q_d_[j] - q[j] + (lambda_ > 0.0 ? qd_ff_[j] / lambda_ : 0.0);
  }
}

}  // namespace centaur
