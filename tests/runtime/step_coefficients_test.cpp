// The per-mode coefficients of an implicit step (runtime/src/step_coefficients.hpp): evaluated
// once per distinct eigenvalue of M, they must equal, bit for bit, those evaluated at every
// eigenvalue alone.
#include "step_coefficients.hpp"

#include <gtest/gtest.h>

#include <erkn/method.hpp>

namespace erkn::test {
namespace {

using detail::first_equal;
using detail::StepCoefficients;

TEST(StepCoefficients, FirstEqualMapsEveryEntryToTheFirstExactlyEqualOne) {
  const double x = 2.5, next = std::nextafter(x, 3.0);
  Eigen::VectorXd lambda(7);
  lambda << 4, x, 1, x, 4, next, x;
  const std::vector<Eigen::Index> first = first_equal(lambda);
  EXPECT_EQ(first, (std::vector<Eigen::Index>{0, 1, 2, 1, 0, 5, 1}));
  // Negative control: one ulp apart is another eigenvalue (index 5 keeps its own).
  EXPECT_NE(first[5], first[1]);
}

// Every accessor of a (lambda-sized) coefficient table at coordinate e.
std::vector<double> values_at(const StepCoefficients<Eigen::ArrayXd>& k, int s, Eigen::Index e) {
  std::vector<double> out;
  for (int i = 0; i < s; ++i) {
    for (const auto& a : {k.phi0c(i), k.hcphi1c(i), k.h2bbar(i), k.hb(i)}) out.push_back(a[e]);
    for (int j = 0; j <= i; ++j) out.push_back(k.abar(i, j)[e]);
  }
  for (const auto& a : {k.phi0m1(), k.hphi1(), k.mhMphi1()}) out.push_back(a[e]);
  return out;
}

TEST(StepCoefficients, SharedAcrossEqualEigenvaluesEqualEachEvaluatedAlone) {
  // A circulant's eigenvalues (each twice but lambda_0 and lambda_{N/2}) in the halfcomplex
  // order, more than the 16 entries from which they are shared, plus one ulp-neighbour.
  const int n = 40;
  Eigen::VectorXd lambda(n + 1);
  for (int k = 0; k < n; ++k) {
    const double s = std::sin(3.14159265358979 * std::min(k, n - k) / n);
    lambda[k] = n * n * s * s;
  }
  lambda[n] = std::nextafter(lambda[3], 0.0);
  const double h = 1.0 / 16;  // v up to 6.25: below the first poles, the series and beyond it
  for (const Method& method : Method::all()) {
    SCOPED_TRACE(std::string(method.name()));
    const StepCoefficients<Eigen::ArrayXd> shared(method, h, lambda);
    for (Eigen::Index e = 0; e < lambda.size(); ++e) {
      const StepCoefficients<Eigen::ArrayXd> alone(method, h, lambda.segment(e, 1));
      EXPECT_EQ(values_at(shared, method.stages(), e), values_at(alone, method.stages(), 0))
          << "coordinate " << e;
    }
  }
}

}  // namespace
}  // namespace erkn::test
