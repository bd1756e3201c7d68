#pragma once
// The filter of the line search (Fletcher & Leyffer; Ipopt's variant): pairs (constraint violation theta,
// barrier objective phi); a trial point is acceptable if no pair dominates it, and below theta_max. With Ipopt's
// filter reset heuristic.
#include <cstddef>
#include <utility>
#include <vector>

namespace centaur::ocp_solver {

class Filter {
 public:
  /// A new solve: no entries, and the reset heuristic's budget restored.
  void start(double theta_max) {
    reset(theta_max);
    heuristic_resets_ = 0;
  }
  /// A new barrier problem (Ipopt resets its line search): no entries, the heuristic's count starts over.
  void reset(double theta_max) {
    theta_max_ = theta_max;
    entries_.clear();
    last_rejection_by_filter_ = false;
    rejections_in_a_row_ = 0;
  }
  bool acceptable(double theta, double phi) const { return belowThetaMax(theta) && notDominated(theta, phi); }
  bool belowThetaMax(double theta) const { return theta <= theta_max_; }
  bool notDominated(double theta, double phi) const {
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
  std::size_t size() const { return entries_.size(); }

  // Ipopt's filter reset heuristic (its max_filter_resets = 5 and filter_reset_trigger = 5): a trial point that
  // passes the test against the current point may still be rejected by the filter. When the last rejection before
  // an accepted trial was the filter's in kResetTrigger accepted steps in a row, the filter is emptied, so that
  // entries from earlier iterations stop blocking the steps; at most kMaxResets times per solve.
  static constexpr int kResetTrigger = 5, kMaxResets = 5;
  void rejectedByFilter() { last_rejection_by_filter_ = true; }
  void rejectedByCurrentPoint() { last_rejection_by_filter_ = false; }
  /// A trial point was accepted (before its entry, if any, is added). Returns whether the filter was emptied.
  bool accepted() {
    bool emptied = false;
    if (heuristic_resets_ < kMaxResets) {
      if (!last_rejection_by_filter_) {
        rejections_in_a_row_ = 0;
      } else if (++rejections_in_a_row_ >= kResetTrigger) {
        reset(theta_max_);
        ++heuristic_resets_;
        emptied = true;
      }
    }
    last_rejection_by_filter_ = false;
    return emptied;
  }
  int heuristicResets() const { return heuristic_resets_; }

 private:
  double theta_max_ = 0.0;
  std::vector<std::pair<double, double>> entries_;
  bool last_rejection_by_filter_ = false;
  int rejections_in_a_row_ = 0, heuristic_resets_ = 0;
};

}  // namespace centaur::ocp_solver
