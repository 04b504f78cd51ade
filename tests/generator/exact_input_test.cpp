// Constants reach the generator exactly: a decimal in a `diagonal` equation is the rational it
// writes (not a 17-digit float), and phi_j(w v) for a rational w that is not the square of a
// rational (w = a 70-digit decimal) has the right Taylor coefficients [v^k] = (-w)^k/(2k+j)!.
#include <gtest/gtest.h>

#include <sstream>

#include "derive.hpp"
#include "phi.hpp"

namespace erkn::gen {
namespace {

// 70 significant digits: far beyond a double and beyond GiNaC's default 17 digits.
const char* const kDecimal =
    "0.03420918108337656312592770951841336071516842785325106619798359050282062";
const GiNaC::numeric kRational(
    GiNaC::numeric("3420918108337656312592770951841336071516842785325106619798359050282062") /
    GiNaC::numeric(10).power(71));

MethodSpec one_stage(const std::string& diagonal) {
  std::istringstream in("method T\nrkn TR\nsource test\nstages 1\norder 2\nc 1/2\nd 1\ndiagonal " +
                        diagonal + "\n");
  return read_specs(in).at(0);
}

TEST(ExactInput, DecimalInDiagonalIsExact) {
  Derived m = derive(one_stage(std::string("abar11 == ") + kDecimal));
  const Qs& a0 = m.coefficients[abar_index(1, 1, 1)].series[0];
  EXPECT_FALSE(a0.is_approx()) << a0.to_string();
  EXPECT_TRUE(a0 == Qs(kRational)) << a0.to_string();
}

TEST(ExactInput, DecimalInDiagonalNegativeControl) {
  // One digit less is a different rational: the comparison above can fail.
  Derived m = derive(one_stage(
      "abar11 == 0.0342091810833765631259277095184133607151684278532510661979835905028206"));
  EXPECT_FALSE(m.coefficients[abar_index(1, 1, 1)].series[0] == Qs(kRational));
}

TEST(ExactInput, PhiOfANonSquareRationalFrequency) {
  GiNaC::symbol v("v");
  for (int j : {0, 1, 3}) {
    std::vector<Qs> series = taylor(to_rational(phi(j, kRational * v), {}, v), 4);
    GiNaC::numeric fact = 1;
    for (int k = 1; k <= j; ++k) fact *= k;
    for (int k = 0; k < 4; ++k) {
      const GiNaC::numeric expect = (-kRational).power(k) / fact;
      EXPECT_LT(std::abs((series[k] - Qs(expect)).to_double()),
                1e-45 * std::abs(expect.to_double()))
          << "phi" << j << " [v^" << k << "] = " << series[k].to_string();
      fact *= (2 * k + j + 1) * (2 * k + j + 2);
    }
  }
}

}  // namespace
}  // namespace erkn::gen
