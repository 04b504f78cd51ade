#include "interpolate.hpp"

#include <algorithm>
#include <cmath>

namespace ex {

std::optional<double> cost_to_tolerance(const std::vector<CurvePoint>& points, double tolerance) {
  std::optional<double> cost;
  for (size_t i = 0; i + 1 < points.size() && !cost; ++i) {
    const CurvePoint& a = points[i];
    const CurvePoint& b = points[i + 1];
    if (!(a.error >= tolerance && b.error <= tolerance && b.error > 0)) continue;
    if (!std::isfinite(a.error) || a.error == b.error) {
      cost = b.cost;  // no log-log line from a failed run
    } else {
      const double s =
          (std::log(tolerance) - std::log(a.error)) / (std::log(b.error) - std::log(a.error));
      cost = std::exp(std::log(a.cost) + s * (std::log(b.cost) - std::log(a.cost)));
    }
  }
  if (cost)
    for (const CurvePoint& p : points)
      if (p.error <= tolerance) cost = std::min(*cost, p.cost);
  return cost;
}

}  // namespace ex
