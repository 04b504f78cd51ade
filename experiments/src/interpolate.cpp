#include "interpolate.hpp"

#include <cmath>

namespace ex {

std::optional<double> cost_to_tolerance(const std::vector<CurvePoint>& points, double tolerance) {
  for (size_t i = 0; i + 1 < points.size(); ++i) {
    const CurvePoint& a = points[i];
    const CurvePoint& b = points[i + 1];
    if (!(a.error >= tolerance && b.error <= tolerance && b.error > 0)) continue;
    if (!std::isfinite(a.error)) return b.cost;  // no log-log line from a failed run
    if (a.error == b.error) return b.cost;
    const double s =
        (std::log(tolerance) - std::log(a.error)) / (std::log(b.error) - std::log(a.error));
    return std::exp(std::log(a.cost) + s * (std::log(b.cost) - std::log(a.cost)));
  }
  return std::nullopt;
}

}  // namespace ex
