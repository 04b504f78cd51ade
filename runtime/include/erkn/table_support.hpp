// What the emitted coefficient functions (generated/src/tables.cpp) call. Hand-written.
#pragma once

#include <cmath>
#include <limits>

#include "erkn/generated/tables.hpp"

namespace erkn::generated::support {

/// An error constant the certificate could not give: every condition checked holds.
inline constexpr double kNotReached = std::numeric_limits<double>::quiet_NaN();

/// sin(t)/t, with its limit 1 at t = 0.
inline double sinc(double t) { return t == 0.0 ? 1.0 : std::sin(t) / t; }
inline long double sincl(long double t) { return t == 0.0L ? 1.0L : std::sin(t) / t; }

/// sum_k a[k] v^k over the kSeriesTerms stored Taylor coefficients.
inline double horner(const double* a, double v) {
  double sum = 0.0;
  for (int k = kSeriesTerms - 1; k >= 0; --k) sum = sum * v + a[k];
  return sum;
}

}  // namespace erkn::generated::support
