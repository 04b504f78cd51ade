// Common factors of a quotient's numerator and denominator. With rational frequencies
// w = n / L, every trig polynomial is A(x, C) + S B(x, C) in C = cos(x/L), S = sin(x/L)
// (cos(n t) = T_n(cos t), sin(n t) = sin t U_(n-1)(cos t)); a polynomial gcd of the four parts
// is a factor of num and den, and dividing it out removes zeros of den that num shares (such
// as cos(x/4) at v = 4 pi^2 for the nodes c = (1/4, 1/2, ...)), which are not poles.
#pragma once

#include "trig.hpp"

namespace erkn::gen {

/// num/den with the common factors in cos(x/L) (and sin(x/L)) divided out; unchanged if there
/// are none, or if a frequency or coefficient is not exact and rational in its field.
Rational cancel_common(const Rational& r);

}  // namespace erkn::gen
