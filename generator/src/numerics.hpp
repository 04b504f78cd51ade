// Numerical facts about a derived coefficient that the runtime needs: its real poles, and
// where its closed form stops being accurate so that the Taylor series must take over.
#pragma once

#include <vector>

#include "derive.hpp"
#include "trig.hpp"

namespace erkn::gen {

inline constexpr double kPoleSearchMax = 10000.0;

/// Real poles of num/den in v in (0, vmax], ascending, each to < 1e-15 relative: zeros of den
/// (sign changes, and double zeros found as zeros of den') where num does not vanish.
/// Throws if a zero of den is also a zero of num (a removable singularity away from 0).
std::vector<double> real_poles(const Rational& r, double vmax);

/// Smallest v_switch from {0, 2^-10, ..., 2^6} such that the closed form loses at most 5 bits
/// to the cancellation that makes it 0/0 at v = 0 (checked at v_switch, 1.5 and 2 v_switch)
/// and the Taylor series (kSeriesTerms terms, as doubles) is accurate to 1e-17 below it.
double series_switch(const Rational& r, const std::vector<double>& series);

/// Real poles in v in (0, kPoleSearchMax] and v_switch of a derived coefficient, into `k`.
void locate_poles(Coefficient& k);

}  // namespace erkn::gen
