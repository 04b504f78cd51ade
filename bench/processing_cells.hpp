// Processed methods (psi = pi o K o pi^-1) against the best unprocessed method of the registry,
// for erkn_modified_kick_benchmark --processing FILE: per scene and tolerance each processed
// method's cheapest run to tol and the best unprocessed one's (bests as in the main table: the
// coarsest n = 2 * 2^(k/8) that meets tol), re-timed interleaved (15 rounds, construction +
// integrate + q() as a user calls them, thread CPU time, medians of the times and of the
// per-round ratios to the unprocessed best); then the cost of output: the best processed and
// the best unprocessed run with an observer every k steps (each observed state costs pi).
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "tolerance_scenes.hpp"

namespace bench {

/// The CPU seconds of one run of m at h with an observer every `every` steps (0: none).
inline double observed_run(const ToleranceScene& s, const erkn::Method& m, double h, long every) {
  const double t0 = thread_seconds();
  erkn::Integrator it(m, erkn::problems::system(s.problem), h, s.problem.q0, s.problem.p0);
  double sink = 0;
  if (every > 0)
    it.integrate(
        s.problem.t_error,
        [&](double, const Eigen::VectorXd& q, const Eigen::VectorXd&) { sink += q[0]; }, every);
  else
    it.integrate(s.problem.t_error);
  sink += it.q()[0];
  const double cpu = thread_seconds() - t0;
  return std::isfinite(sink) ? cpu : kInf;
}

inline double median_of(std::vector<double> x) {
  std::sort(x.begin(), x.end());
  return x[x.size() / 2];
}

/// rounds x (one run of each of `runs`, in turn): the median CPU of each, and of each one's
/// per-round ratio to the first.
struct Interleaved {
  std::vector<double> cpu, ratio;
};
inline Interleaved interleaved(const std::vector<std::function<double()>>& runs, int rounds) {
  std::vector<std::vector<double>> t(runs.size()), r(runs.size());
  for (int k = 0; k < rounds; ++k)
    for (size_t i = 0; i < runs.size(); ++i) {
      t[i].push_back(runs[i]());
      r[i].push_back(t[i].back() / t[0].back());
    }
  Interleaved out;
  for (size_t i = 0; i < runs.size(); ++i)
    out.cpu.push_back(median_of(t[i])), out.ratio.push_back(median_of(r[i]));
  return out;
}

}  // namespace bench
