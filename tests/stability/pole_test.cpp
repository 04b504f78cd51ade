// A step size whose h^2 omega^2 sits on a pole of the coefficients: the integrator refuses it
// with an error naming the pole; a step size 0.1 % away is accepted. The poles come from the
// method registry (the generator), not from this file.
#include <gtest/gtest.h>

#include <cmath>
#include <erkn/problems.hpp>
#include <string>

#include "support.hpp"

namespace erkn {
namespace {

std::string refusal(const Method& m, const System& sys, double h, Eigen::Index d) {
  try {
    Integrator run(m, sys, h, Eigen::VectorXd::Constant(d, 0.1), Eigen::VectorXd::Zero(d));
    run.step();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(Poles, StepSizeOnAPoleIsRefusedWithAClearError) {
  int poles_checked = 0;
  for (const Method& m : Method::all()) {
    for (double pole : m.poles()) {
      if (pole > 100) break;  // the charted range
      const double omega2 = 4.0, h = std::sqrt(pole / omega2);
      const std::string what = refusal(m, test::test_equation(h * h * omega2, 0.5, h), h, 1);
      EXPECT_NE(what.find("pole"), std::string::npos) << m.name() << ": '" << what << "'";
      EXPECT_NE(what.find(std::string(m.name())), std::string::npos) << what;
      // The message names the pole to 6 significant digits at least.
      EXPECT_NE(what.find(std::to_string(pole).substr(0, 6)), std::string::npos)
          << what << " vs " << pole;
      // Negative control: 0.1 % away the same system runs.
      const double h_off = h * std::sqrt(1.001);
      EXPECT_EQ(refusal(m, test::test_equation(h_off * h_off * omega2, 0.5, h_off), h_off, 1), "")
          << m.name();
      ++poles_checked;
    }
  }
  EXPECT_GE(poles_checked, 6);  // SERKN2s3: 3, SERKN2s4: 1, SERKN3s4(1), (2): 2 each
}

// The same for one eigenvalue of a structured M: sine-Gordon's circulant M (problem 1), with h
// chosen so that h^2 lambda_max is the first pole of SERKN3s4(1). RKN limits have no poles.
TEST(Poles, OneEigenvalueOfACirculantMOnAPoleIsEnough) {
  const int N = 32;
  const System sys = problems::system(problems::sine_gordon(N));
  const double lambda_max = sys.M.eigenvalues().maxCoeff();
  const Method& m = Method::by_name("SERKN3s4(1)");
  ASSERT_FALSE(m.poles().empty());
  const double h = std::sqrt(m.poles()[0] / lambda_max);
  EXPECT_NE(refusal(m, sys, h, N).find("pole"), std::string::npos);
  EXPECT_EQ(refusal(Method::by_name("RKN3s4(1)"), sys, h, N), "");
  EXPECT_EQ(refusal(m, sys, 0.999 * h, N), "");
}

// What a pole does to S: only abar_ii blows up, the stage is then frozen (Q_i -> 0 on the test
// equation) and S(V, z) has a finite limit at the pole. Linear stability is therefore continuous
// through a pole; what breaks is the stage equation: near a pole h^2 |abar_ii| |grad^2 U| > 1 for
// any nonlinearity, so fixed point fails and every step needs Newton (sine-Gordon below).
TEST(Poles, StabilityMatrixIsContinuousThroughAPole) {
  int checked = 0;
  for (const Method& m : Method::all())
    for (double p : m.poles()) {
      if (p > 100) break;
      // The jump of tr S across the pole is no larger than its change over an equal distance
      // beside the pole (continuity), and S stays O(1).
      const double d = 1e-5;
      for (double z : {-5.0, 1.0, 10.0}) {
        const StabilityMatrix a = stability_matrix(m, p * (1 - d), z);
        const StabilityMatrix b = stability_matrix(m, p * (1 + d), z);
        const StabilityMatrix c = stability_matrix(m, p * (1 + 3 * d), z);
        EXPECT_LE(std::abs(a.trace() - b.trace()), 2 * std::abs(c.trace() - b.trace()) + 1e-9)
            << m.name() << " pole " << p << " z=" << z;
        EXPECT_LT(std::abs(a.trace()), 10) << m.name() << " pole " << p << " z=" << z;
      }
      ++checked;
    }
  EXPECT_GE(checked, 6);
}

TEST(Poles, NearAPoleFixedPointFailsAndNewtonRunsEveryStep) {
  const problems::Problem sg = problems::sine_gordon(32);
  const Eigen::VectorXd &q0 = sg.q0, &p0 = sg.p0;
  const System sys = problems::system(sg);
  const double lambda_max = sys.M.eigenvalues().maxCoeff();
  const Method& m = Method::by_name("SERKN3s4(1)");
  const double pole = m.poles()[0];
  auto fallbacks = [&](double v) {
    const double h = std::sqrt(v / lambda_max);
    Integrator run(m, sys, h, q0, p0);
    for (int n = 0; n < 20; ++n) run.step();
    return run.statistics().newton_fallbacks;
  };
  EXPECT_GE(fallbacks(pole * (1 + 1e-4)), 20);  // every step
  EXPECT_EQ(fallbacks(pole * 0.9), 0);          // negative control
}

}  // namespace
}  // namespace erkn
