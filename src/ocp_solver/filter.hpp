#pragma once
// The filter of the line search (Fletcher & Leyffer; Ipopt's variant): pairs (constraint violation theta,
// barrier objective phi); a trial point is acceptable if no pair dominates it, and below theta_max.
#include <utility>
#include <vector>

namespace centaur::ocp_solver {

class Filter {
 public:
  void reset(double theta_max) {
    theta_max_ = theta_max;
    entries_.clear();
  }
  bool acceptable(double theta, double phi) const {
    if (!(theta <= theta_max_)) return false;
    for (const auto& [t, p] : entries_)
      if (theta >= t && phi >= p) return false;
    return true;
  }
  /// Add (theta, phi) and drop the entries it dominates.
  void add(double theta, double phi) {
    std::vector<std::pair<double, double>> kept;
    for (const auto& e : entries_)
      if (!(e.first >= theta && e.second >= phi)) kept.push_back(e);
    kept.emplace_back(theta, phi);
    entries_.swap(kept);
  }
  double thetaMax() const { return theta_max_; }

 private:
  double theta_max_ = 0.0;
  std::vector<std::pair<double, double>> entries_;
};

}  // namespace centaur::ocp_solver
