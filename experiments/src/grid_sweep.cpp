#include "grid_sweep.hpp"

#include <algorithm>
#include <cmath>

namespace ex {
namespace {

constexpr double kMargin = 1.15;  // aim this far past the tolerance, on the side still missing

// n (e / tolerance)^(1/p): the step count of error `tolerance` if error ~ h^p.
double order_predicts(const Measurement& m, double tolerance, int order) {
  const double e = std::max(m.error, 1e-6 * tolerance);  // (an exact run: predict far coarser)
  return double(m.steps) * std::pow(e / tolerance, 1.0 / std::max(order, 1));
}

}  // namespace

double predicted_steps(const std::vector<Measurement>& ms, double tolerance, int order) {
  const Measurement* best = nullptr;
  for (const Measurement& m : ms)
    if (m.ok() && (!best || std::abs(std::log(m.error / tolerance)) <
                                std::abs(std::log(best->error / tolerance))))
      best = &m;
  return best ? order_predicts(*best, tolerance, order) : 0;
}

std::vector<Measurement> predicted_bracket(const Solver& solver, const Problem& problem,
                                           const Vec& q_ref, double tolerance, long start,
                                           const SweepPolicy& policy, int max_runs) {
  std::vector<Measurement> ms;
  long n = std::clamp(start, 1L, policy.max_steps);
  for (int run = 0; run < max_runs; ++run) {
    const Measurement m = measure(solver, problem, problem.t_error, n, q_ref, policy.timing);
    ms.insert(std::upper_bound(
                  ms.begin(), ms.end(), m,
                  [](const Measurement& a, const Measurement& b) { return a.steps < b.steps; }),
              m);
    // hi: fewest steps within tolerance; lo: most steps below hi that are beyond it or failed.
    long hi = 0, lo = 0;
    for (const Measurement& x : ms)
      if (x.ok() && x.error <= tolerance && !hi) hi = x.steps;
    for (const Measurement& x : ms)
      if (x.steps < hi || !hi)
        if (!x.ok() || x.error > tolerance) lo = std::max(lo, x.steps);
    if (hi && lo) {
      const bool lo_ok = std::any_of(ms.begin(), ms.end(),
                                     [&](const Measurement& x) { return x.steps == lo && x.ok(); });
      if (lo_ok || hi <= lo + 1 || double(hi) <= 1.05 * double(lo)) break;  // bracketed
    }
    long next;
    if (!m.ok())
      next = hi ? (n + hi) / 2 : 2 * n;
    else if (m.error > tolerance)
      next =
          std::max(n + 1, long(std::ceil(kMargin * order_predicts(m, tolerance, solver.order()))));
    else
      next =
          std::min(n - 1, long(std::floor(order_predicts(m, tolerance, solver.order()) / kMargin)));
    if (hi) next = std::min(next, hi - 1);
    next = std::max(next, lo + 1);
    if (next > policy.max_steps) next = n < policy.max_steps ? policy.max_steps : 0;
    if (next < 1 ||
        std::any_of(ms.begin(), ms.end(), [&](const Measurement& x) { return x.steps == next; }))
      break;
    n = next;
  }
  return ms;
}

}  // namespace ex
