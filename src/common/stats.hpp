#pragma once
// Order statistics of timing samples (benchmarks, run summaries). Take the samples by value: they are sorted.
#include <algorithm>
#include <cmath>
#include <vector>

namespace centaur {

/// Median (mean of the two middle values for an even count); 0 for no sample.
inline double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/// The p-quantile (0 < p <= 1) as the smallest sample with at least a fraction p of the samples at or below it;
/// 0 for no sample.
inline double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const double rank = std::ceil(p * static_cast<double>(v.size())) - 1.0;
  const std::size_t i = static_cast<std::size_t>(std::clamp(rank, 0.0, static_cast<double>(v.size() - 1)));
  return v[i];
}

}  // namespace centaur
