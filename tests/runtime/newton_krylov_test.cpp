// The stage solver beyond d = 256: Newton-Krylov (GMRES, directional differences of grad U,
// preconditioned in M's eigenbasis) solves stages where fixed-point iteration diverges, with
// the same result as the dense Newton of d = 1 on decoupled coordinates, and fails clearly where
// a stage has no solution.
#include <gtest/gtest.h>

#include "problems.hpp"

namespace erkn::test {
namespace {

constexpr int kD = 300;  // above the dense-LU limit (256)

// Decoupled coordinates: M diagonal, grad U_k = kappa q_k + sin q_k; kappa makes
// h^2 abar_ii kappa >> 1, so fixed-point iteration diverges on every method.
System decoupled(const Eigen::VectorXd& m, double kappa) {
  System s;
  s.M = m.size() == 1 ? Stiffness::scalar(m[0]) : Stiffness::diagonal(m);
  s.gradient = [kappa](const Eigen::VectorXd& q, Eigen::VectorXd& g) {
    g = kappa * q.array() + q.array().sin();
  };
  return s;
}

TEST(NewtonKrylov, SolvesStagesFixedPointCannotAndAgreesWithDenseNewtonPerCoordinate) {
  const double h = 0.1, kappa = 5000;
  Eigen::VectorXd m(kD), q0(kD), p0(kD);
  for (int k = 0; k < kD; ++k) {
    m[k] = 1 + 8.0 * k / kD;
    q0[k] = std::sin(0.1 * k);
    p0[k] = std::cos(0.07 * k);
  }
  for (const Method& method : Method::all()) {
    if (method.is_explicit()) continue;  // abar_ii = 0: no stage equation
    SCOPED_TRACE(std::string(method.name()));
    Integrator big(method, decoupled(m, kappa), h, q0, p0);
    for (int n = 0; n < 5; ++n) big.step();
    EXPECT_GT(big.statistics().newton_fallbacks, 0);  // fixed point did not solve them
    EXPECT_EQ(big.statistics().hessian_evaluations, 0);
    double worst = 0;
    for (int k = 0; k < kD; k += 37) {
      Integrator one(method, decoupled(m.segment(k, 1), kappa), h, q0.segment(k, 1),
                     p0.segment(k, 1));
      for (int n = 0; n < 5; ++n) one.step();
      worst = std::max({worst, std::abs(one.q()[0] - big.q()[k]) / (1 + std::abs(one.q()[0])),
                        std::abs(one.p()[0] - big.p()[k]) / (1 + std::abs(one.p()[0]))});
    }
    EXPECT_LT(worst, 1e-9);
  }
}

TEST(NewtonKrylov, NegativeControlOneNewtonIterationCannotProveConvergence) {
  // The same kind of stage with Newton limited to one iteration (no contraction measured): the
  // step must fail with the stage error and leave the state unchanged.
  Eigen::VectorXd m = Eigen::VectorXd::Constant(kD, 2.0), q0 = Eigen::VectorXd::Constant(kD, 0.3),
                  p0 = Eigen::VectorXd::Zero(kD);
  Options o;
  o.max_newton_iterations = 1;
  Integrator run(Method::by_name("SERKN2s4"), decoupled(m, 5000), 0.1, q0, p0, o);
  EXPECT_THROW(run.step(), Error);
  EXPECT_EQ(run.q(), q0);
}

TEST(NewtonKrylov, StageWithoutSolutionIsAnError) {
  System s;
  s.M = Stiffness::scalar(1);
  s.gradient = [](const Eigen::VectorXd& q, Eigen::VectorXd& g) { g = 1e5 * q.array().sign(); };
  const Eigen::VectorXd q0 = Eigen::VectorXd::Constant(kD, 0.01), p0 = Eigen::VectorXd::Zero(kD);
  for (const Method& m : methods_of(Kind::erkn)) {
    if (m.is_explicit()) continue;  // abar_ii = 0: no stage equation
    SCOPED_TRACE(std::string(m.name()));
    Integrator run(m, s, 0.1, q0, p0);
    try {
      run.step();
      ADD_FAILURE() << "no error";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("did not converge"), std::string::npos) << e.what();
    }
    EXPECT_EQ(run.q(), q0);
    EXPECT_EQ(run.t(), 0.0);
  }
}

// A v near a pole of stage i's abar_ii with |h^2 abar_ii(v)| >= 3 (the fixed point then diverges
// on that mode with |grad^2 U| ~ 1), or a negative number when none of the method's poles gives
// one.
double near_pole_v(const Method& method, double h) {
  for (double pole : method.poles())
    for (double offset : {1e-2, 3e-3, 1e-3, 3e-4}) {
      const double v = pole * (1 + offset);
      const Coefficients c = method.at(v);
      for (int i = 0; i < c.s; ++i)
        if (h * h * std::abs(c.abar(i, i)) >= 3) return v;
    }
  return -1;
}

TEST(NewtonKrylov, ModeNearAPoleConvergesAndAgreesWithDenseNewtonOnIt) {
  // One coordinate of M at a v next to a pole of some abar_ii, the others far from every pole;
  // grad U = sin q: only that mode makes the fixed point diverge. Its coordinate alone (d = 1,
  // dense Newton with the exact Jacobian) is the reference.
  const double h = 0.1;
  Eigen::VectorXd m(kD), q0(kD), p0(kD);
  for (int k = 0; k < kD; ++k) {
    m[k] = 1 + 8.0 * k / kD;
    q0[k] = std::sin(0.1 * k);
    p0[k] = std::cos(0.07 * k);
  }
  int tested = 0;
  for (const Method& method : methods_of(Kind::erkn)) {
    const double v = near_pole_v(method, h);
    if (method.is_explicit() || v < 0) continue;
    SCOPED_TRACE(std::string(method.name()));
    m[0] = v / (h * h);
    Integrator big(method, decoupled(m, 0), h, q0, p0);
    for (int n = 0; n < 5; ++n) big.step();
    EXPECT_GT(big.statistics().newton_fallbacks, 0);  // (else this tests nothing)
    Integrator one(method, decoupled(m.head(1), 0), h, q0.head(1), p0.head(1));
    for (int n = 0; n < 5; ++n) one.step();
    EXPECT_NEAR(big.q()[0], one.q()[0], 1e-9 * (1 + std::abs(one.q()[0])));
    EXPECT_NEAR(big.p()[0], one.p()[0], 1e-9 * (1 + std::abs(one.p()[0])));
    ++tested;
  }
  EXPECT_GT(tested, 0);
}

// grad U = kappa q + sin q plus a deterministic noise of relative size `noise` (a different value
// at every call), and the number of calls.
System noisy(const Eigen::VectorXd& m, double kappa, double noise, long& calls) {
  System s = decoupled(m, kappa);
  s.gradient = [kappa, noise, &calls](const Eigen::VectorXd& q, Eigen::VectorXd& g) {
    g = kappa * q.array() + q.array().sin();
    unsigned long x = 88172645463325252ul + 7919ul * ++calls;
    for (Eigen::Index k = 0; k < g.size(); ++k) {
      x ^= x << 13, x ^= x >> 7, x ^= x << 17;  // xorshift64
      g[k] *= 1 + noise * (double(x >> 11) * 0x1.0p-53 - 0.5);
    }
  };
  return s;
}

TEST(NewtonKrylov, StallAboveRoundoffLevelFailsFastNamingIt) {
  // Noise of 1e-9 in grad U leaves Newton-Krylov changing Q by ~1e-8 forever: the step must fail
  // after a few non-contracting iterations (as many gradient calls whatever the iteration limit),
  // name the stall and Options::roundoff_level, and leave the state unchanged.
  const Eigen::VectorXd m = Eigen::VectorXd::Constant(kD, 2.0),
                        q0 = Eigen::VectorXd::Constant(kD, 0.3), p0 = Eigen::VectorXd::Zero(kD);
  std::vector<long> calls_until_error;
  for (int limit : {20, 200}) {
    long calls = 0;
    Options o;
    o.max_newton_iterations = limit;
    Integrator run(Method::by_name("SERKN2s4"), noisy(m, 5000, 1e-9, calls), 0.1, q0, p0, o);
    const long before = calls;
    try {
      run.step();
      ADD_FAILURE() << "no error";
    } catch (const Error& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("stopped contracting"), std::string::npos) << what;
      EXPECT_NE(what.find("Options::roundoff_level"), std::string::npos) << what;
    }
    EXPECT_EQ(run.q(), q0);
    calls_until_error.push_back(calls - before);
  }
  EXPECT_EQ(calls_until_error[0], calls_until_error[1]);
  EXPECT_LT(calls_until_error[0], 200);
}

TEST(NewtonKrylov, NegativeControlNoiseBelowRoundoffLevelConverges) {
  // The same noisy stage with Options::roundoff_level above the noise: accepted as stagnation.
  const Eigen::VectorXd m = Eigen::VectorXd::Constant(kD, 2.0),
                        q0 = Eigen::VectorXd::Constant(kD, 0.3), p0 = Eigen::VectorXd::Zero(kD);
  long calls = 0;
  Options o;
  o.roundoff_level = 1e-5;
  Integrator run(Method::by_name("SERKN2s4"), noisy(m, 5000, 1e-9, calls), 0.1, q0, p0, o);
  EXPECT_NO_THROW(run.step());
  EXPECT_GT(run.statistics().newton_fallbacks, 0);
}

}  // namespace
}  // namespace erkn::test
