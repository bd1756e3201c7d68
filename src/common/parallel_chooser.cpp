#include "common/parallel_chooser.hpp"

#include <algorithm>

namespace centaur::common {

double ParallelChooser::median3(const std::array<double, kHistory>& v, int samples) {
  static_assert(kHistory == 3, "the median below is that of up to three samples");
  const double a = v[0], b = v[1], c = v[2];
  if (samples == 1) return a;
  if (samples == 2) return 0.5 * (a + b);
  return std::max(std::min(a, b), std::min(std::max(a, b), c));
}

bool ParallelChooser::parallel(int section) {
  Section& s = sec_[section];
  if (mode_ != Mode::kAuto) {
    ++s.calls[mode_ == Mode::kParallel];
    return mode_ == Mode::kParallel;
  }
  const Way &in = s.way[0], &par = s.way[1];
  const int n = s.calls[0] + s.calls[1];
  bool p;
  if (s.again >= 0) {
    p = s.again == 1;  // a trial of the other way that came out faster: once more, to confirm
    s.again = -1;
  } else if (s.recorded == 0 || par.samples == 0) {
    p = true;  // the first call, not compared, then the first sample
  } else if (in.samples == 0) {
    p = par.waitMedian() <= kWaitTrigger;  // no reason to try the calling thread alone until it waits
  } else if (par.median() <= in.median()) {
    p = !(par.waitMedian() > kWaitTrigger && n % kExploreSlow == 0);
  } else {
    p = n % kExplore == 0;
  }
  ++s.calls[p];
  return p;
}

void ParallelChooser::record(int section, bool parallel, double seconds_per_unit, double wait_fraction) {
  Section& s = sec_[section];
  if (s.recorded++ == 0) return;
  Way& w = s.way[parallel];
  const Way& other = s.way[!parallel];
  if (w.samples > 0 && other.samples > 0 && w.median() > other.median() && seconds_per_unit < other.median())
    s.again = parallel;
  w.last[w.samples % kHistory] = seconds_per_unit;
  w.wait[w.samples % kHistory] = wait_fraction;
  ++w.samples;
}

}  // namespace centaur::common
