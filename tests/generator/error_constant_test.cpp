// Error constants (certify.hpp): the norms of the residuals of the first failing power are the
// sizes of the leading local error terms. Property: a step made of two substeps theta h and
// (1 - theta) h of a method of order p has, at leading order, the sum of their local errors, so
// every residual of power p + 1 scales by theta^(p+1) + (1 - theta)^(p+1), and so does the
// constant (per power of eps too, where no lower eps-power error is carried into it).
#include <gtest/gtest.h>

#include <cmath>

#include "certify.hpp"

namespace erkn::gen {
namespace {

using GiNaC::numeric;

struct Splitting {
  const char* name;
  std::vector<Qs> c, d;
};

std::vector<Splitting> splittings() {
  const Qs r3 = Qs(0, 1, 3);  // sqrt(3)
  // Yoshida's triple jump: x1 = 1/(2 - 2^(1/3)), x0 = 1 - 2 x1 (approximate arithmetic)
  const Qs x1 = Qs::approximate(1 / (2 - GiNaC::pow(2, GiNaC::numeric(1, 3))));
  const Qs x0 = Qs(1) - Qs(2) * x1, half = Qs(numeric(1, 2));
  return {{"Strang", {half}, {Qs(1)}},
          {"SABA2", {(Qs(3) - r3) / Qs(6), (Qs(3) + r3) / Qs(6)}, {half, half}},
          {"Yoshida4", {x1 * half, x1 + x0 * half, x1 + x0 + x1 * half}, {x1, x0, x1}}};
}

// The method's step split into substeps theta h and (1 - theta) h.
Splitting composed(const Splitting& m, const Qs& theta) {
  Splitting out{m.name, {}, {}};
  for (size_t i = 0; i < m.c.size(); ++i)
    out.c.push_back(theta * m.c[i]), out.d.push_back(theta * m.d[i]);
  for (size_t i = 0; i < m.c.size(); ++i)
    out.c.push_back(theta + (Qs(1) - theta) * m.c[i]), out.d.push_back((Qs(1) - theta) * m.d[i]);
  return out;
}

Certificate certificate(const Splitting& m) {
  return certify(explicit_series(m.c, m.d, 6), false, 7);
}

double factor(double theta, int power) {
  return std::pow(theta, power) + std::pow(1 - theta, power);
}

TEST(ErrorConstant, TwoSubstepsScaleItByTheSumOfTheirPowers) {
  for (const Splitting& m : splittings())
    for (const numeric& theta : {numeric(1, 2), numeric(1, 3)}) {
      const Certificate one = certificate(m), two = certificate(composed(m, Qs(theta)));
      const double th = theta.to_double();
      ASSERT_EQ(two.order, one.order) << m.name;
      ASSERT_TRUE(std::isfinite(one.error_constant) && one.error_constant > 0) << m.name;
      EXPECT_NEAR(two.error_constant / one.error_constant, factor(th, one.order + 1), 1e-12)
          << m.name << ", theta " << th;
      // Negative control: the exponent of the global error (p) does not fit.
      EXPECT_GT(std::abs(two.error_constant / one.error_constant - factor(th, one.order)), 1e-3)
          << m.name;
      for (size_t K = 0; K < one.generalized.size(); ++K) {
        if (K > 0 && one.generalized[K] > one.generalized[K - 1]) break;  // carried errors
        if (one.generalized[K] == one.max_power) continue;
        EXPECT_NEAR(two.generalized_error_constant[K] / one.generalized_error_constant[K],
                    factor(th, one.generalized[K] + 1), 1e-12)
            << m.name << ", eps^" << K + 1;
      }
    }
}

TEST(ErrorConstant, IsTheNormOverThePowersOfEpsThatFailFirst) {
  for (const Splitting& m : splittings()) {
    const Certificate cert = certificate(m);
    double sum = 0;
    for (size_t K = 0; K < cert.generalized.size(); ++K)
      if (cert.generalized[K] == cert.order)
        sum += cert.generalized_error_constant[K] * cert.generalized_error_constant[K];
    EXPECT_NEAR(std::sqrt(sum), cert.error_constant, 1e-14 * cert.error_constant) << m.name;
  }
}

TEST(ErrorConstant, IsNotANumberWhenNoConditionChecked) {
  // Strang certified only up to h^2: no failing condition was checked.
  const Splitting m = splittings()[0];
  const Certificate cert = certify(explicit_series(m.c, m.d, 6), false, 2);
  EXPECT_EQ(cert.order, 2);
  EXPECT_TRUE(std::isnan(cert.error_constant));
}

}  // namespace
}  // namespace erkn::gen
