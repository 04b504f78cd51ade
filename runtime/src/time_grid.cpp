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

namespace {

// plan_to's refusals, out of its way (their messages' formatting made it save every register and
// reserve 424 bytes of stack at each call).
[[noreturn, gnu::cold, gnu::noinline]] void refuse_end(double t_end, double t0) {
  throw Error("t_end = " + format(t_end, 17) +
              " is not finite or lies before t = " + format(t0, 17));
}
[[noreturn, gnu::cold, gnu::noinline]] void refuse_steps(double span, double steps, double h) {
  throw Error("t_end - t = " + format(span) + " needs " + format(steps) +
              " steps of h = " + format(h) +
              ", more than the step-count limit 2^53 = " + format(TimeGrid::kMaxSteps, 17) +
              " (beyond it t0 + n h is not exact); integrate in shorter spans or with a "
              "larger h");
}
[[noreturn, gnu::cold, gnu::noinline]] void refuse_unresolved(double h, double t0, double t_end) {
  throw Error("h = " + format(h) + " is below the round-off of t = " + format(t0) +
              " and t_end = " + format(t_end) + ": the time grid cannot be resolved");
}

}  // namespace

TimeGrid::Plan TimeGrid::plan_to(double t_end) const {
  const double t0 = t(), span = t_end - t0, tol = tolerance(t_end);
  if (!std::isfinite(span) || span < -tol) refuse_end(t_end, t0);
  if (span <= tol) return {0, false};
  const double steps = span / h_;
  // (before any conversion to an integer: no overflow)
  if (!(steps <= kMaxSteps)) refuse_steps(span, steps, h_);
  if (h_ <= 2 * tol) refuse_unresolved(h_, t0, t_end);
  // The grid points around t_end; t_end within round-off of one of them is it. The plan is the
  // last grid index N >= n_ with t0_ + N h <= t_end + tol (non-decreasing in N), whichever N the
  // loops start from: here the nearest, so t_end on the grid (an output time's usual case) needs
  // no correction, and in integers (at(N) forms double(N) as ahead(N - n_) forms double(n_ + n):
  // the same double, exact below 2^53), without a floor (a dozen dependent instructions here). The
  // start is counted from t0_, not from t(): its quotient does not wait for t() (with it, the
  // plan was one chain of ~50 cycles, 27 % of the time an output time adds; Duffing, perf).
  const double limit = t_end + tol;
  // (a rounded quotient, may be off by an ulp's worth: the loops correct it; >= n_ as the plan)
  long N = std::max(long((t_end - t0_) / h_ + 0.5), n_);
  while (N > n_ && at(N) > limit) --N;
  while (at(N + 1) <= limit) ++N;
  return {N - n_, std::abs(at(N) - t_end) > tol};
}

void TimeGrid::require_output_times(double t_end,
                                    const Eigen::Ref<const Eigen::VectorXd>& times) const {
  // (Compared with the round-off window of plan_to: 0.1 + 0.2 is 0.3.)
  const double t0 = t();
  for (Eigen::Index k = 0; k < times.size(); ++k) {
    const double tau = times[k];
    if (!std::isfinite(tau) || (k > 0 && tau < times[k - 1]) || tau < t0 - window(t0, tau, h_) ||
        tau > t_end + window(t_end, tau, h_))
      throw Error("output time " + std::to_string(k) + " = " + format(tau, 17) +
                  " is not finite, not ascending, or outside [t, t_end] = [" + format(t0, 17) +
                  ", " + format(t_end, 17) + "]");
  }
}

}  // namespace erkn
