#include "interpolate.hpp"

#include <algorithm>
#include <cmath>

namespace ex {

std::optional<size_t> bracketing_pair(const std::vector<CurvePoint>& points, double tolerance) {
  for (size_t i = 0; i + 1 < points.size(); ++i)
    if (points[i].error >= tolerance && points[i + 1].error <= tolerance && points[i + 1].error > 0)
      return i;
  return std::nullopt;
}

std::optional<double> cost_to_tolerance(const std::vector<CurvePoint>& points, double tolerance) {
  const auto i = bracketing_pair(points, tolerance);
  if (!i) return std::nullopt;
  const CurvePoint &a = points[*i], &b = points[*i + 1];
  double cost = b.cost;  // no log-log line from a failed run
  if (std::isfinite(a.error) && a.error != b.error) {
    const double s =
        (std::log(tolerance) - std::log(a.error)) / (std::log(b.error) - std::log(a.error));
    cost = std::exp(std::log(a.cost) + s * (std::log(b.cost) - std::log(a.cost)));
  }
  for (const CurvePoint& p : points)
    if (p.error <= tolerance) cost = std::min(cost, p.cost);
  return cost;
}

}  // namespace ex
