#include "sweep.hpp"

#include <algorithm>
#include <cmath>

namespace ex {
namespace {

constexpr double kBisectionGap = 1.05;

void sort_by_steps(std::vector<Measurement>& ms) {
  std::sort(ms.begin(), ms.end(),
            [](const Measurement& a, const Measurement& b) { return a.steps < b.steps; });
}

// Round-off floor reached: the error no longer falls when the step shrinks.
bool stalled(const Measurement& coarse, const Measurement& fine) {
  return fine.ok() && coarse.ok() && fine.error > 0.8 * coarse.error && fine.error < 1e-7;
}

}  // namespace

std::vector<Measurement> sweep(const Solver& solver, const Problem& problem, double t_end,
                               const Vec& q_ref, const SweepPolicy& policy,
                               const std::vector<long>& steps) {
  std::vector<Measurement> ms;
  std::vector<long> seeds =
      steps.empty() ? std::vector<long>(problem.paper_steps.begin(), problem.paper_steps.end())
                    : steps;
  // A scene outside the paper (FPU, Henon-Heiles) starts at its energy chart's step.
  if (seeds.empty()) seeds.push_back(std::max(1L, std::lround(t_end / problem.h_energy)));
  for (long n : seeds) ms.push_back(measure(solver, problem, t_end, n, q_ref, policy.timing));
  sort_by_steps(ms);
  if (!steps.empty()) return ms;

  // Larger steps, until the error passes error_high or the method fails.
  while (ms.front().ok() && ms.front().error < policy.error_high && ms.front().steps > 1) {
    const long n = std::max(1L, long(std::floor(double(ms.front().steps) / policy.factor)));
    ms.insert(ms.begin(), measure(solver, problem, t_end, n, q_ref, policy.timing));
  }
  // Smaller steps, until the error passes error_low, stalls at round-off, or costs too much.
  auto finest_ok = [&] {
    return ms.back().ok() && ms.back().error > policy.error_low &&
           !stalled(ms[ms.size() - 2], ms.back());
  };
  while ((!ms.back().ok() || finest_ok()) && ms.back().steps * policy.factor <= policy.max_steps) {
    const long n = long(std::ceil(double(ms.back().steps) * policy.factor));
    ms.push_back(measure(solver, problem, t_end, n, q_ref, policy.timing));
  }
  return ms;
}

std::vector<Measurement> bracket(const Solver& solver, const Problem& problem, double t_end,
                                 const Vec& q_ref, const std::vector<double>& tolerances,
                                 long start, const SweepPolicy& policy) {
  auto run = [&](long n) { return measure(solver, problem, t_end, n, q_ref, policy.timing); };
  const double coarse = *std::max_element(tolerances.begin(), tolerances.end());
  const double fine = *std::min_element(tolerances.begin(), tolerances.end());
  std::vector<Measurement> ms{run(start)};
  while (ms.front().error <= coarse && ms.front().steps > 1)
    ms.insert(ms.begin(), run(ms.front().steps / 2));
  if (ms.back().error > fine) {
    while (ms.back().error > fine && ms.back().steps * 2 <= policy.max_steps)
      ms.push_back(run(ms.back().steps * 2));
    // One more: a finer step can cost less (a stage solver that needed Newton at the coarser).
    if (ms.back().error <= fine && ms.back().steps * 2 <= policy.max_steps)
      ms.push_back(run(ms.back().steps * 2));
  }
  // A failed (unstable) run next to one within the coarsest tolerance: bisect the step count down
  // to a 5% gap, so that the cheapest run within tolerance sits at the stability limit.
  for (size_t i = 0; i + 1 < ms.size(); ++i) {
    while (!ms[i].ok() && ms[i + 1].error <= coarse &&
           double(ms[i + 1].steps) > kBisectionGap * double(ms[i].steps) + 1) {
      Measurement mid = run((ms[i].steps + ms[i + 1].steps) / 2);
      const bool failed = !mid.ok() || mid.error > coarse;
      ms.insert(ms.begin() + long(i) + 1, std::move(mid));
      if (failed)
        ++i;  // the bracket is now (mid, old i+1)
      else if (ms[i + 1].error > coarse)
        break;
    }
  }
  return ms;
}

}  // namespace ex
