// Cost to reach an error tolerance, read off a measured error-vs-cost curve by linear
// interpolation in log-log coordinates between the two measurements that bracket the tolerance.
// Never extrapolates: no bracketing pair, no answer.
#pragma once

#include <optional>
#include <vector>

namespace ex {

struct CurvePoint {
  double cost;   ///< > 0
  double error;  ///< > 0, or +inf for a failed run
};

/// Points in order of increasing work (step count). Uses the first pair (a, b), a before b, with
/// error(a) >= tolerance >= error(b); if the cheapest point already meets the tolerance there is
/// no bracket and the result is empty. If run a failed (error +inf: unstable or refused), that
/// pair gives b's own cost. A measured run within tolerance that costs less than the result (cost
/// need not grow with the step count, e.g. when a stage solver falls back to Newton at large
/// steps) replaces it.
std::optional<double> cost_to_tolerance(const std::vector<CurvePoint>& points, double tolerance);

/// The index a of the pair (a, a + 1) that cost_to_tolerance interpolates between; empty when no
/// pair brackets the tolerance.
std::optional<size_t> bracketing_pair(const std::vector<CurvePoint>& points, double tolerance);

}  // namespace ex
