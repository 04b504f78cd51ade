#include "measure.hpp"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <exception>
#include <limits>
#include <string>

namespace ex {
namespace {

constexpr int kMaxShortRepeats = 1000;
// Shortest timing sample (seconds): shorter runs are timed in batches.
constexpr double kMinSample = 1e-3;
// An error this many times the solution's size means the run blew up.
constexpr double kUnstable = 100;

// Runs per timing sample for a run of `seconds`: enough for min_sample (at most 1000 per ms).
int batch_for(double seconds, double min_sample) {
  return int(
      std::min(1000.0 * min_sample / kMinSample, std::ceil(min_sample / std::max(seconds, 1e-7))));
}

// CPU seconds per run of `batch` consecutive runs; *first receives the first run's result.
double sample(const Solver& solver, const Problem& problem, double h, long steps, int batch,
              RunResult* first) {
  const double start = cpu_seconds();
  RunResult r = solver.run(problem, h, steps, nullptr);
  for (int b = 1; b < batch; ++b) solver.run(problem, h, steps, nullptr);
  const double seconds = (cpu_seconds() - start) / batch;
  if (first) *first = std::move(r);
  return seconds;
}

}  // namespace

double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

Measurement measure(const Solver& solver, const Problem& problem, double t_end, long steps,
                    const Vec& q_ref, const TimingPolicy& timing) {
  Measurement m;
  m.steps = steps;
  m.h = t_end / double(steps);
  m.cpu = std::numeric_limits<double>::infinity();
  double spent = 0;
  int batch = 1;  // runs per timing sample: short runs are timed in batches of >= kMinSample
  try {
    // Up to `repeats` samples within the budget; very short runs repeat until min_total is spent.
    for (int k = 0; k == 0 || (k < timing.repeats && spent < timing.budget) ||
                    (spent < timing.min_total && k < kMaxShortRepeats);
         ++k) {
      RunResult r;
      const double seconds = sample(solver, problem, m.h, steps, batch, &r);
      spent += seconds * batch;
      // A process clock that did not advance says nothing: such a sample is not kept.
      if (seconds > 0) m.cpu = std::min(m.cpu, seconds);
      if (k == 0 && seconds < kMinSample) batch = batch_for(seconds, kMinSample);
      m.stats = r.stats;
      m.error = (r.q - q_ref).lpNorm<Eigen::Infinity>();
      if (!(m.error <= kUnstable * (1 + q_ref.lpNorm<Eigen::Infinity>()))) {
        m.failure = "unstable (error " + std::to_string(m.error) + ")";
        break;
      }
    }
  } catch (const std::exception& e) {
    m.failure = e.what();
  }
  if (!m.ok()) m.error = std::numeric_limits<double>::infinity();
  return m;
}

double time_again(const Solver& solver, const Problem& problem, const Measurement& m,
                  double min_sample) {
  const int batch = m.cpu < min_sample ? batch_for(m.cpu, min_sample) : 1;
  return sample(solver, problem, m.h, m.steps, batch, nullptr);
}

}  // namespace ex
