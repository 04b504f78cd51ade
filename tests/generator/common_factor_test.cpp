// cancel_common: a factor shared by numerator and denominator is divided out (the quotient is
// the same function, and the shared zero is no longer a zero of the denominator); a quotient
// without a common factor is left as it is.
#include <gtest/gtest.h>

#include <cmath>

#include "cancel.hpp"

namespace erkn::gen {
namespace {

const double kPi = std::acos(-1.0);

// a = 2 + cos(x) - v phi1(v/9), b = phi1(v/9) + v: functions of v with no common factor.
TrigPoly a() {
  return TrigPoly(Qs(2)) + TrigPoly::phi0(Qs(1)) -
         TrigPoly::v() * TrigPoly::phi1(Qs(GiNaC::numeric(1, 3)));
}
TrigPoly b() { return TrigPoly::phi1(Qs(GiNaC::numeric(1, 3))) + TrigPoly::v(); }

bool same_quotient(const Rational& p, const Rational& q) {
  return (p.num * q.den - q.num * p.den).is_zero();
}

TEST(CancelCommon, DividesOutASharedTrigFactor) {
  // cos(x/4) vanishes at x = 2 pi (v = 4 pi^2); so does sin(x/2) = 2 sin(x/4) cos(x/4).
  for (const TrigPoly& f : {TrigPoly::phi0(Qs(GiNaC::numeric(1, 4))),
                            TrigPoly::v() * TrigPoly::phi1(Qs(GiNaC::numeric(1, 2)))}) {
    Rational shared{f * a(), f * b()};
    ASSERT_NEAR(TrigEval(shared.den, 20)(2 * kPi), 0, 1e-12);
    Rational out = cancel_common(shared);
    EXPECT_TRUE(same_quotient(out, Rational{a(), b()}));
    EXPECT_GT(std::abs(TrigEval(out.den, 20)(2 * kPi)), 1e-3);
    EXPECT_NO_THROW(out.den.phi_terms());  // still a function of v
  }
}

TEST(CancelCommon, LeavesCoprimeQuotientsAlone) {
  Rational coprime{a(), b()};
  Rational out = cancel_common(coprime);
  EXPECT_EQ(out.num.terms(), coprime.num.terms());
  EXPECT_EQ(out.den.terms(), coprime.den.terms());
}

}  // namespace
}  // namespace erkn::gen
