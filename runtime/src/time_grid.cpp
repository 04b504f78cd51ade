#include "erkn/time_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "erkn/error.hpp"
#include "format.hpp"

namespace erkn {

void TimeGrid::invalid(double t0, double h) {
  if (!std::isfinite(h) || h <= 0)
    throw Error("the step size h must be finite and > 0; got h = " + format(h));
  throw Error("t = " + format(t0) + " is not finite");
}

bool TimeGrid::resolved() const {
  const double t0 = t();
  return h_ > 2 * window(t0, t0 + h_, h_);
}

void TimeGrid::require_resolved() const {
  if (!resolved())
    throw Error("h = " + format(h_) + " is below the round-off of t = " + format(t(), 17) +
                ": a step would not advance the time (set the state at a smaller t, or use a "
                "larger h)");
}

void TimeGrid::refuse_end(double t_end, double t0) {
  throw Error("t_end = " + format(t_end, 17) +
              " is not finite or lies before t = " + format(t0, 17));
}

void TimeGrid::refuse_steps(double span, double steps, double h) {
  throw Error("t_end - t = " + format(span) + " needs " + format(steps) +
              " steps of h = " + format(h) +
              ", more than the step-count limit 2^53 = " + format(TimeGrid::kMaxSteps, 17) +
              " (beyond it t0 + n h is not exact); integrate in shorter spans or with a "
              "larger h");
}

void TimeGrid::refuse_unresolved(double h, double t0, double t_end) {
  throw Error("h = " + format(h) + " is below the round-off of t = " + format(t0) +
              " and t_end = " + format(t_end) + ": the time grid cannot be resolved");
}

void TimeGrid::require_output_times(double t_end,
                                    const Eigen::Ref<const Eigen::VectorXd>& times) const {
  // Every time admissible, tested as: the first and the last admissible, and each time >= the
  // one before (false for NaN). That is the same: a finite time between two finite ones is
  // finite, and the windows' edges t0 - window(m0, tau) and t_end + window(m1, tau) move by at
  // most 4 eps |dtau| as tau moves by dtau, so no time after the first crosses the lower one and
  // none before the last the upper one. (The first failure is looked for only then. Callgrind,
  // Duffing Strang with 20 output times: admissible on every time was 28 instructions per output
  // time, this 6.)
  const Eigen::Index n = times.size();
  if (n == 0) return;
  const double t0 = t(), m0 = std::max(std::abs(t0), h_), m1 = std::max(std::abs(t_end), h_);
  const double none = -std::numeric_limits<double>::infinity();
  bool all = admissible(times[0], none, t0, t_end, m0, m1) &
             admissible(times[n - 1], none, t0, t_end, m0, m1);
  for (Eigen::Index k = 1; k < n; ++k) all &= times[k] >= times[k - 1];
  if (!all) [[unlikely]]
    refuse_output_times(t_end, times);
}

void TimeGrid::refuse_output_times(double t_end,
                                   const Eigen::Ref<const Eigen::VectorXd>& times) const {
  const double t0 = t(), m0 = std::max(std::abs(t0), h_), m1 = std::max(std::abs(t_end), h_);
  double prev = -std::numeric_limits<double>::infinity();
  Eigen::Index k = 0;
  while (admissible(times[k], prev, t0, t_end, m0, m1)) prev = times[k++];
  throw Error("output time " + std::to_string(k) + " = " + format(times[k], 17) +
              " is not finite, not ascending, or outside [t, t_end] = [" + format(t0, 17) + ", " +
              format(t_end, 17) + "]");
}

}  // namespace erkn
