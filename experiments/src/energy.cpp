#include "energy.hpp"

#include <algorithm>
#include <cmath>
#include <exception>

namespace ex {

EnergyCurve energy_errors(const Solver& solver, const Problem& pr, double h,
                          const std::vector<double>& t_ends) {
  EnergyCurve curve{h, t_ends, {}, {}, {}};
  const double h0 = pr.energy(pr.q0, pr.p0);
  double running = 0;
  size_t next = 0;
  std::vector<long> checkpoints;
  for (double t : t_ends) checkpoints.push_back(std::lround(t / h));
  long n = 0;
  Observer observe = [&](double, const Vec& q, const Vec& p) {
    ++n;
    const double e = std::abs(pr.energy(q, p) - h0);
    running = std::isfinite(e) ? std::max(running, e) : HUGE_VAL;
    while (next < checkpoints.size() && n == checkpoints[next]) {
      curve.max_error.push_back(running);
      ++next;
    }
  };
  try {
    curve.stats = solver.run(pr, h, checkpoints.back(), &observe).stats;
    if (!std::isfinite(running)) curve.failure = "non-finite energy (unstable)";
  } catch (const std::exception& e) {
    curve.failure = e.what();
  }
  return curve;
}

}  // namespace ex
