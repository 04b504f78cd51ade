// StageSolver's fixed-point iteration and its contraction bookkeeping (included by
// stage_solver.hpp).
#pragma once

namespace erkn::detail {

// Fixed point Q <- r_i - h^2 abar_ii(V) g(Q) from start_stage's r_i and Q_0. True when
// converged, or when the updates stall below Options::roundoff_level (a tolerance under the
// round-off noise); G(i) then holds the gradient of the last iterate but one (no confirming
// evaluation).
// The tests take the iteration's squared sums as they come (Change: X = |dQ|^2, N = the larger
// |Q|^2 of the two iterates, delta^2 = X / N) and the previous iteration's delta, known since that
// iteration ended: multiplied out, no test waits for a division or a square root (within,
// verdict). delta = sqrt(X / N) is formed only for the next iteration, while its gradient is
// evaluated. (Tested on delta with a divide and a square root, that chain was 43-57 % of P2's
// samples in this loop: perf, d = 1.)
template <class Space, class Coef>
[[gnu::always_inline]] inline bool StageSolver<Space, Coef>::fixed_point(int i, const Start& start,
                                                                         long& evaluations) {
  Iterates x{
      start.r_hat, start.Q_hat,  scratch(x_.Q_hat_new), scratch(G(i)), scratch(x_.g_first_hat),
      G(i),        start.abar_ii};
  // A new measurement's theta (record_contraction), formed before the first evaluation, whose
  // latency hides its division and root: formed at the measurement, at the end of a stage, they
  // were ~19 % of this loop's samples (perf, P2, SERKN1s2(1)).
  if (StageRecord& r = record_[i]; r.due_den2 > 0)
    set_theta(r, std::sqrt(r.due_num2 / r.due_den2)), r.due_den2 = 0;
  // The first iteration on its own (the common stage ends there, contraction_proves): one reduce
  // of |dQ|^2, |Q_new|^2 and |Q|^2. (Inside the loop its tests of `it` and its spills were ~25
  // of P2's instructions per stage.)
  if constexpr (kStagedIterate) x.finite_Q = std::isfinite(start.norm2_Q);  // (checked_iterate)
  const std::array<double, 2> change = iterate(i, 1, x, evaluations);
  const auto sums = space_.reduce(std::array{
      change[0], change[1], kStagedIterate ? start.norm2_Q : space_.squared_norm(x.Q_hat), 0.0});
  const Change c = in_range(sums[0], std::max(sums[1], sums[2]));
  swap_views(x.Q_hat, x.Q_hat_new);
  if (c.X > 0 && contraction_proves(i, c)) return true;
  x.g_first_hat = x.G;
  return iterate_on(i, x, c, sums[0], sums[1], evaluations);
}

// One iteration at x.Q_hat: x.G = its force, x.Q_hat_new = r_i - h^2 abar_ii x.G; returns this
// process's |Q_new - Q|^2 and |Q_new|^2. (start_stage formed the physical Q of the first iterate;
// with kStagedIterate the last iteration staged the next one's.)
template <class Space, class Coef>
[[gnu::always_inline]] inline std::array<double, 2> StageSolver<Space, Coef>::iterate(
    int i, int it, Iterates& x, long& evaluations) {
  if (it > 1) {
    if constexpr (kStagedIterate)
      space_.to_physical_staged(x_.Q);
    else
      space_.to_physical(x.Q_hat, x_.Q);
  }
  stage_force(i, x.Q_hat, x.G, evaluations, true, x.finite_Q);  // (and one stage iteration)
  if constexpr (Space::kFixed) x.G_i = x.G;                     // (a view: G is G_i)
  const std::array<double, 2> change = next_iterate(x);
  if constexpr (kSumChecks) x.finite_Q = checked_iterate(i, change[1]);
  return change;
}

// x.Q_hat_new = r_i - h^2 abar_ii x.G and this process's {|Q_new - Q|^2, |Q_new|^2}: in one pass
// that also stages Q_new for the inverse transform (kStagedIterate), else as expressions.
template <class Space, class Coef>
[[gnu::always_inline]] inline std::array<double, 2> StageSolver<Space, Coef>::next_iterate(
    Iterates& x) {
  if constexpr (kStagedIterate) {
    return space_.iterate(x.r_hat, x.abar_ii, x.G, x.Q_hat, x.Q_hat_new);
  } else {
    x.Q_hat_new = x.r_hat - x.abar_ii * x.G;
    return {space_.squared_norm(x.Q_hat_new - x.Q_hat), space_.squared_norm(x.Q_hat_new)};
  }
}

// kSumChecks: the checks of g and of the next iterate Q on |Q_new|^2 (norm2_Q_new), which the
// iteration sums anyway. A non-finite g makes it non-finite: the forward transform spreads a
// non-finite entry over its outputs, and Q_new = r - abar G keeps it (abar G is NaN where abar =
// 0), as does the weighted sum of non-negative terms. So g is scanned, and the error thrown as
// the scan after the call threw it, only when the sum is not finite. A finite sum bounds each
// |Q_new| by 2^512 sqrt(d), so the physical Q the inverse transform makes of it is finite
// (explicit_passes.hpp, kStageBound): true when the next gradient needs no scan of Q. (The two
// scans per gradient were ~235 of SERKN2s3's ~7,650 instructions per grad U at sine-Gordon N = 32,
// callgrind.)
template <class Space, class Coef>
bool StageSolver<Space, Coef>::checked_iterate(int i, double norm2_Q_new) const {
  if (std::isfinite(norm2_Q_new)) return true;
  if (!all_finite(x_.g.data(), x_.g.size())) non_finite_gradient(i, *at_);
  return false;
}

// The iterations after the first (c: its change, first2 its |dQ|^2, norm2_Q its |Q_new|^2).
// |dQ| / max(|Q_new|, |Q_old|) in eigen coordinates, so a converged stage needs no inverse
// transform. Both iterates: an iterate at 0 (a 2-cycle r -> 0 -> r) must not make delta huge and
// the next theta ~ 0, which would pass the stopping test without converging. One reduce: |dQ|^2,
// |Q_new|^2 and at the second iteration the contraction's (record_contraction).
template <class Space, class Coef>
[[gnu::always_inline]] inline bool StageSolver<Space, Coef>::iterate_on(int i, Iterates& x,
                                                                        Change c, double first2,
                                                                        double norm2_Q,
                                                                        long& evaluations) {
  double delta_old = std::sqrt(c.X / c.N);
  int extra = 0;  // iterations after convergence from a cold start (reset_tightening)
  const int max_iterations = options_.max_fixed_point_iterations;
  for (int it = 2; it <= max_iterations; ++it) {
    const std::array<double, 2> change = iterate(i, it, x, evaluations);
    const bool measure = it == 2 && first2 > 0 && measures_contraction(delta_old);
    if (measure) x.g_first_hat = x.abar_ii * (x.G - x.g_first_hat);
    const auto sums = space_.reduce(
        std::array{change[0], change[1], 0.0, measure ? space_.squared_norm(x.g_first_hat) : 0.0});
    c = in_range(sums[0], std::max(sums[1], norm2_Q));
    norm2_Q = sums[1];
    swap_views(x.Q_hat, x.Q_hat_new);
    if (it == 2 && first2 > 0) record_contraction(i, first2, c, delta_old, sums[3]);
    // A first update below round-off (X = 0) proves nothing: the guess then holds the
    // extrapolation's error below round-off, and stopping there let RKN3s4(2) drift in energy
    // over 1e6 steps of P3 (h = 1e-3).
    if (c.X == 0) return true;
    const Verdict v = verdict(i, it, c, delta_old, extra);
    if (v == Verdict::converged) return true;
    if (v == Verdict::failed) return keep_iterate(x.Q_hat), false;
  }
  // Out of iterations: accept only round-off noise, or a converged stage's extra iterations.
  if (extra > 0 || c.X <= square(options_.roundoff_level) * c.N) return true;
  return keep_iterate(x.Q_hat), false;
}

// x_.Q_hat = the last iterate Q_hat of a failed fixed point (Newton-Krylov may start from it):
// stored (a value), or the view of it taken (a view of x_.Q_hat or x_.Q_hat_new).
template <class Space, class Coef>
void StageSolver<Space, Coef>::keep_iterate(const Work& Q_hat) {
  if constexpr (Space::kFixed)
    x_.Q_hat = Q_hat;
  else if (Q_hat.data() != x_.Q_hat.data())
    swap_views(x_.Q_hat, x_.Q_hat_new);
}

// The decision after iteration it > 1 (c: its change, X > 0; delta_old: the one before, replaced
// by this iteration's delta when it iterates on): converged once theta/(1-theta) delta <=
// tolerance (theta = delta / delta_old; reset_tightening may ask for more), failed when theta >=
// max_theta above round-off (stagnation at round-off converges) or when the tolerance is out of
// reach (too_slow), else iterate on. (delta's square root is formed only on the way to another
// iteration, and too_slow's theta from it with one division.)
// (Always inlined: GCC left it out of line in a larger step, a call per iteration: P2,
// RKN1s2(1) +22 instructions per grad U.)
template <class Space, class Coef>
[[gnu::always_inline]] inline auto StageSolver<Space, Coef>::verdict(int i, int it, Change c,
                                                                     double& delta_old,
                                                                     int& extra) const -> Verdict {
  if (within(c, delta_old, options_.tolerance)) {
    if (!reset_tightening(c, delta_old, extra)) return Verdict::converged;
    delta_old = std::sqrt(c.X / c.N);
    return Verdict::iterate;
  }
  if (extra > 0) return Verdict::converged;  // (converged before; this iteration did not contract)
  const bool noise = c.X <= square(options_.roundoff_level) * c.N;  // delta <= roundoff_level
  if (c.X >= square(options_.max_theta * delta_old) * c.N)          // theta >= max_theta
    return noise ? Verdict::converged : Verdict::failed;
  const double delta = std::sqrt(c.X / c.N);
  if (!noise && too_slow(i, it, delta / delta_old, delta_old)) return Verdict::failed;
  delta_old = delta;
  return Verdict::iterate;
}

// theta/(1-theta) delta <= tol, theta = delta / delta_old < 1, delta^2 = X / N: as
// delta^2 + tol delta <= tol delta_old, i.e. R = tol delta_old N - X >= 0 and
// tol^2 X N <= R^2 (multiplied by N, then squared). False when delta_old = 0.
template <class Space, class Coef>
bool StageSolver<Space, Coef>::within(Change c, double delta_old, double tol) {
  const double R = tol * delta_old * c.N - c.X;
  return R >= 0 && tol * tol * c.X * c.N <= R * R;
}

// (X, N) as they are where the products of `within` neither overflow nor underflow (N in
// [kLowNorm2, kHighNorm2]: |Q| from 1e-50 to 1e50), else (X / N, 1) (relative_change2).
template <class Space, class Coef>
auto StageSolver<Space, Coef>::in_range(double change2, double norm2) -> Change {
  if (norm2 >= kLowNorm2 && norm2 <= kHighNorm2) return {change2, norm2};
  return {relative_change2(change2, norm2), 1.0};
}

// After a reset of the starting-guess history (construction, set_state, a shorter step, a
// monitor rollback) the guess is poor, and theta/(1-theta) |dQ| can pass the tolerance while
// the stage is still off by ~1e-11 (FPU, omega = 50, h omega = 1: SERKN3s4(1) 1.0e-11 relative
// after one step, SERKN4s6 6.7e-12, against stages iterated to round-off). There the fixed
// point iterates on after converging, up to kResetExtra times, until the estimate is within
// kResetShare of the tolerance. Its stopping test stays the tolerance: a tighter one made
// steps at half the predicted fixed-point limit fall back to Newton (ff85219, reverted).
// True when one more iteration is due; counts it in `extra`.
template <class Space, class Coef>
bool StageSolver<Space, Coef>::reset_tightening(Change c, double delta_old, int& extra) const {
  if (predictor_.has_history() || extra >= kResetExtra ||
      within(c, delta_old, kResetShare * options_.tolerance))
    return false;
  ++extra;
  return true;
}

// change2 / norm2 (delta^2), norm2 the larger squared norm of the two iterates (floored: an
// iterate of norm below 1e-300 counts as 1e-300).
template <class Space, class Coef>
double StageSolver<Space, Coef>::relative_change2(double change2, double norm2) {
  if (change2 == 0) return 0;
  if (norm2 >= std::numeric_limits<double>::min()) return change2 / norm2;
  const double delta = std::sqrt(change2) / std::max(std::sqrt(norm2), 1e-300);
  return delta * delta;
}

// Whether reaching the tolerance at theta = delta / delta_old (< max_theta) would take more
// iterations than are left, or more than Newton's last solve of this stage cost: K more
// iterations leave theta^(K+1)/(1-theta) delta = theta^(K+2)/(1-theta) delta_old.
template <class Space, class Coef>
bool StageSolver<Space, Coef>::too_slow(int i, int it, double theta, double delta_old) const {
  int left = options_.max_fixed_point_iterations - it;
  if (record_[i].newton_cost > 0) left = std::min(left, int(record_[i].newton_cost));
  double power = theta * theta;  // theta^(left + 2) by squaring
  for (double base = theta; left > 0; left >>= 1, base *= base)
    if (left & 1) power *= base;
  return power * delta_old > options_.tolerance * (1 - theta);
}

// The contraction theta of stage i's iteration is a property of h, M and U near the solution:
// measured at a second iteration (record_contraction), it lets a later first iteration stop
// once theta/(1-theta) |dQ| weight_i <= kFirstShare * tolerance with theta = kThetaSafety times
// the measurement (no second evaluation to measure it again). Measured afresh at every second
// iteration, and forced by one every kThetaRefresh solves of that stage. The step then uses
// g(Q_0), whose error reaches (q, p) through bbar_i and b_i rather than abar_ii: weight_i =
// max(1, |bbar_i| / |abar_ii|, |b_i| / (h |abar_ii|)). kFirstShare: that error is the
// extrapolation's, systematic, so it adds up over the steps (a converged second iteration leaves
// round-off): at the full tolerance P1's error at 1e-9 changed by up to 25% against stages
// iterated to round-off (erkn_stage_evaluations, "vs tol 0"), at a hundredth of it by < 2e-11.
// theta_s/(1-theta_s) delta weight_i <= kFirstShare * tolerance with theta_s = kThetaSafety theta
// < 1/2 (else never), delta^2 = X / N: multiplied out, X (theta_s weight_i)^2 <= (kFirstShare
// tolerance (1 - theta_s))^2 N (theta_s = 0 passes), the factors formed with theta (set_theta).
// Without theta, or with theta_s >= 1/2, proof_N = -1 fails the test (X > 0, N > 0: in_range);
// the solves are counted there too, harmlessly: theta is set only after a measurement, which
// restarts the count. (Tested apart, theta < 0 and the flag were ~5 of ~16 instructions per
// stage, P2.) The count stops at kThetaRefresh (an int counting every solve would overflow).
template <class Space, class Coef>
bool StageSolver<Space, Coef>::contraction_proves(int i, Change c) {
  StageRecord& r = record_[i];
  r.theta_age += r.theta_age < kThetaRefresh;
  return r.theta_age < kThetaRefresh && c.X * r.proof_X <= r.proof_N * c.N;
}

// r.theta = theta and contraction_proves' factors from it. Formed at the stage's next solve,
// before its first evaluation, whose latency hides theta's division and root and these products:
// at the end of the measuring stage they waited on them (perf, P2: SERKN1s2(1) ~6 % more CPU per
// grad U); formed at every first iteration they were ~10 of P2's ~280 instructions per stage.
template <class Space, class Coef>
void StageSolver<Space, Coef>::set_theta(StageRecord& r, double theta) const {
  r.theta = theta;
  const double theta_s = kThetaSafety * theta;
  const double lhs = theta_s * r.weight, rhs = kFirstShare * options_.tolerance * (1 - theta_s);
  r.proof_X = lhs * lhs, r.proof_N = theta_s < 0.5 ? rhs * rhs : -1;
}

// theta along the first update, |h^2 abar_ii (g(Q_1) - g(Q_0))| / |Q_1 - Q_0|, with g(Q_0) in
// g_first_hat and g(Q_1) in G(i). Not the ratio of the updates |Q_2 - Q_1| / |Q_1 - Q_0|: Q_2 =
// r_i - h^2 abar_ii g(Q_1) cancels against r_i, so once the guess is good that ratio measures
// the round-off of Q, not theta (P3, SERKN3s4(1), h = 1/4: |Q_1 - Q_0| ~ 1e-11 |Q|, the ratio
// 1e-5..1e-4 against theta ~ 1e-6), and the first-iteration stop seldom passed. Below ~1e3
// round-offs the first update is not measured: the old measurement is only renewed when the
// ratio does not exceed what it allowed. First-iteration stops on guesses that good keep their
// error systematic over millions of steps (RKN3s4(2) on P3 at h = 1e-3, 1e6 steps: the energy
// error grew 10-fold, 1.4e-12 -> 1.4e-11, when they were allowed; energy_test).
template <class Space, class Coef>
bool StageSolver<Space, Coef>::measures_contraction(double delta_first) {
  return delta_first >= 1e3 * kEps;
}

// (first2: |Q_1 - Q_0|^2; c: the second iteration's change; measure2: |h^2 abar_ii (g(Q_1) -
// g(Q_0))|^2 when measures_contraction(delta_first), and theta = sqrt(measure2 / first2), formed at
// the stage's next solve before fixed_point needs it. Unmeasured, the ratio of the
// updates, delta / delta_first with delta floored at kEps, renews the old theta when it is <=
// kThetaSafety theta.)
template <class Space, class Coef>
void StageSolver<Space, Coef>::record_contraction(int i, double first2, Change c,
                                                  double delta_first, double measure2) {
  StageRecord& r = record_[i];
  if (!measures_contraction(delta_first)) {
    const double bound = kThetaSafety * r.theta * delta_first;  // on delta
    if (r.theta >= 0 && (c.X == 0 ? kEps <= bound : c.X <= bound * bound * c.N)) r.theta_age = 0;
    return;
  }
  r.due_num2 = measure2, r.due_den2 = first2;
  r.theta_age = 0;
}

}  // namespace erkn::detail
