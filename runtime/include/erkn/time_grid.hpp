// The time grid of a fixed-step run, t_n = t0 + n h: one definition for erkn::Integrator, the MPI
// GridIntegrator and (through Integrator) Python. t0 is the start, or the time of the last
// set_state, change of h or shorter step; t_n is formed from t0 and the integer n, never summed
// step by step, so no round-off accumulates over the steps.
//
// Round-off window: a time within tolerance(t_end) = 4 eps max(|t|, |t_end|, h) of a grid point
// (the error of forming t0 + n h and of the caller's own sum, e.g. 0.1 + 0.2) counts as that grid
// point. A time off the grid is reached by whole steps to the last grid point before it and one
// shorter step (plan_to); the caller restarts the grid there.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>

namespace erkn {

class TimeGrid {
 public:
  /// At most this many steps per plan: beyond 2^53 the grid t0 + n h is not exact.
  static constexpr double kMaxSteps = 9007199254740992.0;

  /// The grid t0 + n h from n = 0; erkn::Error unless t0 is finite and h finite and > 0 (the one
  /// place a step size is validated).
  TimeGrid(double t0, double h) : t0_(t0), h_(h) {
    if (!(std::isfinite(h) && h > 0 && std::isfinite(t0))) [[unlikely]]
      invalid(t0, h);
  }

  double t() const { return t0_ + double(n_) * h_; }
  double h() const { return h_; }
  /// The grid point `steps` whole steps after t().
  double ahead(long steps) const { return t0_ + double(n_ + steps) * h_; }
  /// Steps of h taken (one by default).
  void advance(long steps = 1) { n_ += steps; }
  /// The grid starts over at t (after a shorter step to t, or a new state at t).
  void restart(double t) { t0_ = t, n_ = 0; }
  /// The grid of step size h from t() on (validated as the constructor does).
  TimeGrid with_step(double h) const { return TimeGrid(t(), h); }
  /// The grid of this step size from t0 on (validated as the constructor does).
  TimeGrid with_start(double t0) const { return TimeGrid(t0, h_); }

  /// The round-off window of times near t() and t_end.
  double tolerance(double t_end) const { return window(t(), t_end, h_); }
  /// False when a step of h would not move t() beyond its round-off (e.g. h = 0.1 at t = 1e20).
  bool resolved() const;
  /// erkn::Error unless resolved().
  void require_resolved() const;

  struct Plan {
    long whole = 0;        ///< steps of size h
    bool shorter = false;  ///< then one shorter step, of size t_end - ahead(whole)
  };
  /// The way from t() to t_end: t_end on the grid (up to round-off) is reached by whole steps,
  /// else the whole steps stop at the last grid point before it. erkn::Error if t_end is not
  /// finite, lies before t(), needs more than kMaxSteps steps or h is below the round-off.
  /// (Inline: at an output time its call and the unused `shorter` cost ~20 of its ~80
  /// instructions; callgrind, Duffing with 20 output times.)
  [[gnu::always_inline]] Plan plan_to(double t_end) const {
    const double t0 = t(), span = t_end - t0, tol = tolerance(t_end);
    if (!std::isfinite(span) || span < -tol) [[unlikely]]
      refuse_end(t_end, t0);
    if (span <= tol) return {0, false};
    const double steps = span / h_;
    // (before any conversion to an integer: no overflow)
    if (!(steps <= kMaxSteps)) [[unlikely]]
      refuse_steps(span, steps, h_);
    if (h_ <= 2 * tol) [[unlikely]]
      refuse_unresolved(h_, t0, t_end);
    // The grid points around t_end; t_end within round-off of one of them is it. The plan is the
    // last grid index N >= n_ with t0_ + N h <= t_end + tol (non-decreasing in N), whichever N the
    // loops start from: here the nearest, so t_end on the grid (an output time's usual case) needs
    // no correction, and in integers (at(N) forms double(N) as ahead(N - n_) forms double(n_ + n):
    // the same double, exact below 2^53), without a floor (a dozen dependent instructions here).
    // The start is counted from t0_, not from t(): its quotient does not wait for t() (with it,
    // the plan was one chain of ~50 cycles, 27 % of the time an output time adds; Duffing, perf).
    const double limit = t_end + tol;
    // (a rounded quotient, may be off by an ulp's worth: the loops correct it; >= n_ as the plan)
    long N = std::max(long((t_end - t0_) / h_ + 0.5), n_);
    while (N > n_ && at(N) > limit) --N;
    while (at(N + 1) <= limit) ++N;
    return {N - n_, std::abs(at(N) - t_end) > tol};
  }
  /// erkn::Error naming the first of `times` that is not finite, not ascending, or outside
  /// [t(), t_end] beyond the round-off window.
  void require_output_times(double t_end, const Eigen::Ref<const Eigen::VectorXd>& times) const;

 private:
  double t0_, h_;
  long n_ = 0;

  // Grid point N counted from t0_ (ahead(N - n_)).
  double at(long N) const { return t0_ + double(N) * h_; }

  // The constructor's error for (t0, h) (out of line: a valid grid costs its comparisons only).
  [[noreturn]] static void invalid(double t0, double h);
  // plan_to's refusals, out of its way (their messages' formatting made it save every register and
  // reserve 424 bytes of stack at each call).
  [[noreturn, gnu::cold]] static void refuse_end(double t_end, double t0);
  [[noreturn, gnu::cold]] static void refuse_steps(double span, double steps, double h);
  [[noreturn, gnu::cold]] static void refuse_unresolved(double h, double t0, double t_end);
  // require_output_times's test of one time (each comparison evaluated, no branch per comparison).
  // (m0, m1: max(|t0|, h) and max(|t_end|, h), formed once per call: see window.)
  static bool admissible(double tau, double prev, double t0, double t_end, double m0, double m1) {
    return std::isfinite(tau) & !(tau < prev) & !(tau < t0 - window(m0, tau)) &
           !(tau > t_end + window(m1, tau));
  }
  // require_output_times's error, naming the first time that fails admissible.
  [[noreturn, gnu::cold]] void refuse_output_times(
      double t_end, const Eigen::Ref<const Eigen::VectorXd>& times) const;
  // Round-off in forming a time a = t0 + n h near b: a few ulps of the largest magnitude
  // involved, never proportional to n h itself beyond that (issue 12, defect 2).
  // (Inline: out of line it cost a call at every output time, is_now and validation alike.)
  static double window(double a, double b, double h) { return window(std::max(std::abs(a), h), b); }
  // The same with m = max(|a|, h) formed by the caller (once for many b).
  static double window(double m, double b) {
    return 4 * std::numeric_limits<double>::epsilon() * std::max(m, std::abs(b));
  }
};

}  // namespace erkn
