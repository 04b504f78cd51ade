// The phi-functions of the paper, eq. (e), at a scalar v = x^2 >= 0:
//   phi0(v) = cos x,  phi1(v) = sin x / x,  and phi0(v) - 1 = -2 sin^2(x/2) without cancellation.
#pragma once

#include <array>
#include <cmath>

#include "erkn/table_support.hpp"

namespace erkn::detail {

inline double phi0(double v) { return std::cos(std::sqrt(v)); }

inline double phi1(double v) { return generated::support::sinc(std::sqrt(v)); }

/// {phi0(v), phi1(v)}, the same values, from one square root: the compiler then pairs the sine
/// and cosine of x in one sincos (computed apart, each took its own sqrt, which errno keeps the
/// compiler from merging, and its own libm call).
inline std::array<double, 2> phi01(double v) {
  const double x = std::sqrt(v);
  return {std::cos(x), generated::support::sinc(x)};
}
inline double phi0_minus_1(double v) {
  const double s = std::sin(0.5 * std::sqrt(v));
  return -2 * s * s;
}

}  // namespace erkn::detail
