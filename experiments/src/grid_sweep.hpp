// Step counts that bracket a tolerance in few runs, for scenes where one run costs seconds: the
// next step count is the one the method's order predicts from the last error, not a doubling.
#pragma once

#include <vector>

#include "sweep.hpp"

namespace ex {

/// Measurements (sorted by step count) from `start` on, until a run within `tolerance` has a run
/// beyond it (or a failed one) below it, the prediction passes policy.max_steps, or `max_runs`
/// runs are spent. After a run with error e > tolerance at n steps the next count is
/// 1.15 n (e / tolerance)^(1/order), after one with e <= tolerance and nothing beyond the
/// tolerance yet n (e / tolerance)^(1/order) / 1.15; after a failed run (unstable, or a stage that
/// did not converge) the count doubles, or bisects towards a run within tolerance.
std::vector<Measurement> predicted_bracket(const Solver& solver, const Problem& problem,
                                           const Vec& q_ref, double tolerance, long start,
                                           const SweepPolicy& policy, int max_runs = 6);

/// The step count the order predicts for `tolerance` from the run in `ms` closest to it (0 when
/// no run succeeded).
double predicted_steps(const std::vector<Measurement>& ms, double tolerance, int order);

}  // namespace ex
