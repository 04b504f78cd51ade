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

}  // namespace
}  // namespace erkn::test
