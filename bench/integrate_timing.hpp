// Timing for erkn_integrate_benchmark: contenders timed in interleaved rounds (the order rotated
// every round), thread CPU time, each sample `reps` whole runs (setup included), and the ratio
// of two contenders as the median over rounds of their per-round ratio (a load change on the
// shared machine then hits both sides of a ratio alike).
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "thread_seconds.hpp"

namespace bench {

inline double median(std::vector<double> x) {
  if (x.empty()) return NAN;
  std::sort(x.begin(), x.end());
  const size_t n = x.size();
  return n % 2 ? x[n / 2] : 0.5 * (x[n / 2 - 1] + x[n / 2]);
}

struct TimingPlan {
  int rounds = 7;            // interleaved rounds
  double min_sample = 5e-3;  // seconds of CPU per sample (reps runs of the first contender)
};

/// seconds[c][r]: contender c's CPU seconds per run in round r. Every contender runs once
/// untimed first (warm-up: FFTW plans, caches), then `reps` runs per sample, reps chosen so that
/// contender 0's sample takes at least plan.min_sample.
inline std::vector<std::vector<double>> time_rounds(
    const std::vector<std::function<void()>>& contenders, const TimingPlan& plan) {
  const size_t k = contenders.size();
  for (const auto& run : contenders) run();
  const double t0 = thread_seconds();
  contenders[0]();
  const double once = std::max(thread_seconds() - t0, 1e-9);
  const int reps = std::max(1, int(std::ceil(plan.min_sample / once)));
  std::vector<std::vector<double>> seconds(k, std::vector<double>(size_t(plan.rounds)));
  for (int r = 0; r < plan.rounds; ++r)
    for (size_t i = 0; i < k; ++i) {
      const size_t c = (i + size_t(r)) % k;
      const double start = thread_seconds();
      for (int j = 0; j < reps; ++j) contenders[c]();
      seconds[c][size_t(r)] = (thread_seconds() - start) / reps;
    }
  return seconds;
}

/// The median over rounds of a[r] / b[r].
inline double median_ratio(const std::vector<double>& a, const std::vector<double>& b) {
  std::vector<double> r;
  for (size_t i = 0; i < a.size(); ++i) r.push_back(a[i] / b[i]);
  return median(r);
}

}  // namespace bench
