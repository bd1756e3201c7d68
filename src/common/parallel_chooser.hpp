#pragma once
// Whether handing work to a second thread pays on this machine at this moment. On a virtual machine the two vCPUs
// are not always two cores close together, and on any machine the second core may be busy with other work: handing
// a job over and reading its results back can then cost more than doing the job on the calling thread. In auto
// mode each kind of section (the derivatives, a factorization, a pair of solves) runs on both threads as long as
// the calling thread hardly waits for the worker (the median of the last kHistory calls below kWaitTrigger of
// their time). Once it waits more, the section runs on the calling thread alone once, and from then on the way
// with the lower median wall time per unit of work (e.g. per stage factored) runs. The other way is tried again
// every kExplore-th call while the calling thread alone is faster, and every kExploreSlow-th call while both
// threads are faster but the caller still waits; a trial that comes out faster than the way in use is repeated at
// once, so that the medians can change sides within a few calls. The first call of a section warms caches and
// pages and is not compared. A section's results must not depend on the way it runs: this is a choice of speed.
#include <array>

namespace centaur::common {

/// The kinds of section of the planner's interior point, each judged on its own.
enum ParallelSectionKind { kSectionDerivatives = 0, kSectionFactor, kSectionRefactor, kSectionSolves };

class ParallelChooser {
 public:
  enum class Mode { kParallel, kInline, kAuto };
  static constexpr int kSections = 4;
  static constexpr int kHistory = 3;
  static constexpr int kExplore = 16;
  static constexpr int kExploreSlow = 8;
  static constexpr double kWaitTrigger = 0.1;

  void setMode(Mode m) { mode_ = m; }
  Mode mode() const { return mode_; }
  /// Whether the next call of `section` (0..kSections-1) runs on both threads (true) or on the calling one.
  bool parallel(int section);
  /// The wall time per unit of work of the call just made the way parallel() chose,
  /// and the fraction of its wall time the calling thread spent waiting for the worker.
  void record(int section, bool parallel, double seconds_per_unit, double wait_fraction = 0.0);
  /// Calls of `section` so far each way (in every mode).
  int calls(int section, bool parallel) const { return sec_[section].calls[parallel]; }

 private:
  struct Way {
    std::array<double, kHistory> last{}, wait{};  // rings of the latest samples and their wait fractions
    int samples = 0;
    double median() const { return median3(last, samples); }
    double waitMedian() const { return median3(wait, samples); }
  };
  static double median3(const std::array<double, kHistory>& v, int samples);
  struct Section {
    Way way[2];  // [0] inline, [1] parallel
    int calls[2] = {0, 0};
    int recorded = 0;  // record() calls, the first of which is not compared
    int again = -1;    // the way the next call runs regardless (1 parallel, 0 inline), -1: none
  };
  Mode mode_ = Mode::kParallel;
  std::array<Section, kSections> sec_;
};

}  // namespace centaur::common
