// The generator's error constants as the registry carries them (erkn/table.hpp): every method
// (of order below the powers the generator checks) has a finite positive constant, and the
// classical one is the norm of the per-eps-power constants of the powers of eps that fail at
// h^(order+1) (the residuals at that power split by the trees' number of f-vertices).
#include <gtest/gtest.h>

#include <cmath>

#include "erkn/method.hpp"

namespace erkn {
namespace {

// sqrt of the sum of squares of the constants of the eps powers whose order is `order`.
double norm_at(const Method& m, int order) {
  double sum = 0;
  for (size_t K = 0; K < m.generalized_order().size(); ++K)
    if (m.generalized_order()[K] == order) sum += std::pow(m.generalized_error_constant()[K], 2);
  return std::sqrt(sum);
}

TEST(ErrorConstant, EveryMethodHasOne) {
  for (const Method& m : Method::all()) {
    EXPECT_TRUE(std::isfinite(m.error_constant()) && m.error_constant() > 0) << m.name();
    EXPECT_EQ(m.generalized_error_constant().size(), m.generalized_order().size()) << m.name();
  }
}

TEST(ErrorConstant, IsTheNormOfTheEpsPowersThatFailFirst) {
  int checked = 0;
  for (const Method& m : Method::all()) {
    if (m.kind() == Kind::rkn) continue;
    // The tables hold 6 significant digits.
    EXPECT_NEAR(norm_at(m, m.order()), m.error_constant(), 2e-5 * m.error_constant()) << m.name();
    // Negative control: the eps powers of the next order are other residuals.
    EXPECT_GT(std::abs(norm_at(m, m.order() + 1) - m.error_constant()), 1e-3 * m.error_constant())
        << m.name();
    ++checked;
  }
  EXPECT_GT(checked, 10);
}

}  // namespace
}  // namespace erkn
