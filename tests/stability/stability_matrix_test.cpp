// S(V, z) of paper §4.1 against one actual step of erkn::Integrator on y'' + omega^2 y = -eps y,
// and det S = 1 (symplecticity) over the charted grid.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "support.hpp"

namespace erkn {
namespace {

double max_abs(const StabilityMatrix& S) {
  return std::max({std::abs(S.s11), std::abs(S.s12), std::abs(S.s21), std::abs(S.s22)});
}

double distance(const StabilityMatrix& a, const StabilityMatrix& b) {
  return max_abs({a.s11 - b.s11, a.s12 - b.s12, a.s21 - b.s21, a.s22 - b.s22});
}

// Sample points of the charted rectangle V in [0, 100], z in [-50, 50] with V + z > 0 (the test
// equation's hypothesis), skipping poles and singular N = I + z Abar. Both stage solver paths
// occur: fixed point where h^2 |abar_ii| |eps| < 1, Newton (exact Hessian) elsewhere.
std::vector<std::pair<double, double>> sample_points(const Method& m) {
  std::vector<std::pair<double, double>> pts;
  for (double V : {0.0, 0.37, 2.0, 7.3, 19.0, 33.0, 51.0, 77.0, 99.0})
    for (double z : {-45.0, -13.0, -3.1, -0.2, 0.0, 0.6, 4.0, 17.0, 49.0}) {
      if (V + z <= 0 || !test::away_from_poles(m, V, 1e-2)) continue;
      const StabilityMatrix S = stability_matrix(m, V, z);
      if (!S.finite() || max_abs(S) > 1e3) continue;  // next to a singular line of N
      pts.emplace_back(V, z);
    }
  return pts;
}

// The stage solver stops at theta/(1-theta)|dQ| <= tolerance and uses the gradients of the last
// iterate but one, so a step carries a stage error ~ (bbar_i / abar_ii) * tolerance: up to
// ~5e-13 at the default tolerance 1e-14 for the 3-stage methods (abar_11 = 0.0064). The
// comparison at 1e-13 therefore runs the stage solver at tolerance 1e-16 (it then stops at
// round-off); with the default options it holds to 1e-12.
void expect_step_equals_s(const Options& o, double bound) {
  for (const Method& m : Method::all()) {
    const auto pts = sample_points(m);
    ASSERT_GE(pts.size(), 40u) << m.name();
    double worst = 0;
    for (auto [V, z] : pts)
      for (double h : {0.01, 0.3}) {
        const StabilityMatrix S = stability_matrix(m, V, z);
        const StabilityMatrix T = test::one_step_matrix(m, V, z, h, o);
        const double err = distance(S, T) / std::max(1.0, max_abs(S));
        worst = std::max(worst, err);
        EXPECT_LE(err, bound) << m.name() << " V=" << V << " z=" << z << " h=" << h;
      }
    ::testing::Test::RecordProperty(std::string(m.id_name()) + "_max_rel_error",
                                    std::to_string(worst));
  }
}

TEST(StabilityMatrix, EqualsOneIntegratorStepForEveryMethod) {
  Options tight;
  tight.tolerance = 1e-16;
  expect_step_equals_s(tight, 1e-13);
}

TEST(StabilityMatrix, EqualsOneIntegratorStepWithDefaultOptions) {
  expect_step_equals_s(Options{}, 1e-12);
}

// Negative control: the comparison is sharp enough to tell two 4th-order methods apart.
TEST(StabilityMatrix, ComparisonDistinguishesNeighbouringMethods) {
  const Method& a = Method::by_name("SERKN3s4(1)");
  const Method& b = Method::by_name("SERKN3s4(2)");
  const StabilityMatrix S = stability_matrix(a, 19.0, 4.0);
  const StabilityMatrix T = test::one_step_matrix(b, 19.0, 4.0, 0.3);
  EXPECT_GT(distance(S, T), 1e-6);
  // ... and an ERKN method from its own RKN limit.
  const StabilityMatrix R = test::one_step_matrix(Method::by_name("RKN3s4(1)"), 19.0, 4.0, 0.3);
  EXPECT_GT(distance(S, R), 1e-3);
}

// ERKN methods are exact for eps = 0 (z = 0): S is the rotation of y'' + omega^2 y = 0.
TEST(StabilityMatrix, ErknIsTheExactRotationAtZEqualZero) {
  for (const Method& m : Method::all()) {
    if (m.kind() != Kind::erkn) continue;
    for (double V : {0.5, 9.0, 30.0, 64.0, 99.5}) {
      if (!test::away_from_poles(m, V, 1e-3)) continue;
      const StabilityMatrix S = stability_matrix(m, V, 0.0);
      const double x = std::sqrt(V);
      EXPECT_NEAR(S.s11, std::cos(x), 1e-15) << m.name();
      EXPECT_NEAR(S.s12, std::sin(x) / x, 1e-15) << m.name();
      EXPECT_NEAR(S.s21, -x * std::sin(x), 1e-14) << m.name();
      EXPECT_NEAR(S.s22, std::cos(x), 1e-15) << m.name();
    }
  }
}

// RKN limits see only the total force: S(V, z) = S(0, V + z).
TEST(StabilityMatrix, RknDependsOnlyOnTheTotalForce) {
  for (const Method& m : Method::all()) {
    if (m.kind() != Kind::rkn) continue;
    const StabilityMatrix a = stability_matrix(m, 30.0, -12.0), b = stability_matrix(m, 0.0, 18.0);
    EXPECT_LE(distance(a, b), 1e-15 * std::max(1.0, max_abs(a))) << m.name();
  }
}

// Symplectic: det S = 1 up to round-off relative to |s11 s22| + |s12 s21|, everywhere on the
// charted grid (also next to poles and singular lines, where S is huge). The bound is 1e4 ulp:
// S's entries are themselves sums of larger terms (the pole-free SERKN2s4pf, with constant
// abar_ii, reaches 1.03e-12 on this grid); a perturbed weight gives 1e-6 (next test).
TEST(StabilityMatrix, DeterminantIsOneOverTheChartedGrid) {
  for (const Method& m : Method::all()) {
    const StabilityGrid g = stability_grid(m, 100, -50, 50, 201, 201);
    EXPECT_LE(g.max_det_relative_deviation, 1e4 * std::numeric_limits<double>::epsilon())
        << m.name();
    RecordProperty(std::string(m.id_name()) + "_max_det_dev_bounded",
                   std::to_string(g.max_det_deviation_bounded));
  }
}

// Negative control: a non-symplectic perturbation of the weights (b_1 + 1e-6) breaks det S = 1,
// and classify then refuses to call the point periodic even though |tr S| < 2.
TEST(StabilityMatrix, PerturbedWeightsAreDetectedAsNotSymplectic) {
  const Method& m = Method::by_name("SERKN2s4");
  Coefficients k = m.at(5.0);
  k.b[0] += 1e-6;
  const StabilityMatrix S = stability_matrix(m, k, 5.0, 3.0);
  EXPECT_GT(S.det_relative_deviation(), 1e-8);
  EXPECT_LT(std::abs(S.trace()), 2.0);
  EXPECT_NE(classify(S), StabilityClass::periodic);
  EXPECT_EQ(classify(stability_matrix(m, 5.0, 3.0)), StabilityClass::periodic);
}

TEST(StabilityMatrix, ClassifyUsesTheStatedTraceTolerance) {
  auto rot = [](double tr) {  // det 1, trace tr
    return StabilityMatrix{tr / 2, 1, tr * tr / 4 - 1, tr / 2};
  };
  EXPECT_EQ(classify(rot(1.999)), StabilityClass::periodic);
  EXPECT_EQ(classify(rot(2.0)), StabilityClass::marginal);
  EXPECT_EQ(classify(rot(-2.0 - 0.5 * kTraceTolerance)), StabilityClass::marginal);
  EXPECT_EQ(classify(rot(2.0 + 4 * kTraceTolerance)), StabilityClass::unstable);
  EXPECT_EQ(classify(rot(-2.1)), StabilityClass::unstable);
  EXPECT_NEAR(rot(2.5).spectral_radius(), 2.0, 1e-15);  // eigenvalues 2 and 1/2
  EXPECT_NEAR(rot(-2.5).spectral_radius(), 2.0, 1e-15);
  EXPECT_NEAR(rot(1.0).spectral_radius(), 1.0, 1e-15);
  EXPECT_EQ(classify({std::nan(""), 0, 0, 1}), StabilityClass::singular);
}

}  // namespace
}  // namespace erkn
