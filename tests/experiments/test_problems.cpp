// The three problems: exact solution of P2, gradient/Hessian/energy consistency, M structures.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <boost/math/special_functions/jacobi_elliptic.hpp>
#include <cmath>

#include "problem.hpp"

namespace ex {
namespace {

TEST(Problems, DuffingExactSolutionSatisfiesTheOde) {
  const Problem p = duffing();
  const double k2 = 0.03 * 0.03, d = 1e-4;
  auto q = [&](double t) { return (*p.exact)(t)[0]; };
  EXPECT_NEAR(q(0), 0.0, 1e-15);
  EXPECT_NEAR((q(d) - q(-d)) / (2 * d), 10.0, 1e-5);  // q'(0) = 10
  for (double t = 0.05; t < 10; t += 0.37) {
    const double qdd = (q(t + d) - 2 * q(t) + q(t - d)) / (d * d);
    const double x = q(t);
    EXPECT_NEAR(qdd + 100 * x, k2 * (2 * x * x * x - x), 1e-4) << "t = " << t;
  }
}

TEST(Problems, DuffingEnergyIsConservedByTheExactSolution) {
  const Problem p = duffing();
  const double k = 0.03;
  auto energy_at = [&](double t) {
    double cn = 0, dn = 0;
    const double sn = boost::math::jacobi_elliptic(k / 10, 10 * t, &cn, &dn);
    return p.energy(Vec::Constant(1, sn), Vec::Constant(1, 10 * cn * dn));
  };
  for (double t : {0.3, 1.7, 5.0, 9.9}) EXPECT_NEAR(energy_at(t), energy_at(0), 1e-12);
}

class EachProblem : public ::testing::TestWithParam<int> {
 protected:
  Problem problem() const {
    switch (GetParam()) {
      case 0:
        return sine_gordon(32);
      case 1:
        return duffing();
      case 2:
        return stellar_orbits();
      case 4:
        return erkn::problems::henon_heiles();
      default:  // the stiff scene's kappa scales grad U, U and the Hessian alike
        return sine_gordon(4, 10);
    }
  }
};

TEST_P(EachProblem, GradientAndHessianMatchFiniteDifferences) {
  const Problem p = problem();
  Vec q = p.q0 + 0.3 * Vec::LinSpaced(p.dim(), 0.1, 1.0);
  Vec g;
  p.grad_u(q, g);
  const Eigen::MatrixXd hess = p.hessian_u(q);
  const double d = 1e-6;
  for (int i = 0; i < p.dim(); ++i) {
    Vec qp = q, qm = q, gp, gm;
    qp[i] += d, qm[i] -= d;
    EXPECT_NEAR((p.potential(qp) - p.potential(qm)) / (2 * d), g[i], 1e-7);
    p.grad_u(qp, gp), p.grad_u(qm, gm);
    for (int j = 0; j < p.dim(); ++j) EXPECT_NEAR((gp[j] - gm[j]) / (2 * d), hess(j, i), 1e-7);
  }
}

TEST_P(EachProblem, LongDoubleForceMatchesDoubleForce) {
  const Problem p = problem();
  const Vec q = p.q0 + 0.2 * Vec::LinSpaced(p.dim(), -1.0, 1.0);
  Vec f;
  p.force(q, f);
  VecLD qld(q.data(), q.data() + q.size()), fld(q.size());
  p.force_ld(qld, fld);
  for (int i = 0; i < p.dim(); ++i) EXPECT_NEAR(double(fld[i]), f[i], 1e-10 * (1 + std::abs(f[i])));
}

TEST_P(EachProblem, EigenvaluesAreThoseOfTheDenseMatrix) {
  const Problem p = problem();
  Eigen::VectorXd dense =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(p.M.dense(p.dim())).eigenvalues();
  Vec ours = p.M.eigenvalues(p.dim());
  std::sort(ours.data(), ours.data() + ours.size());
  EXPECT_LT((dense - ours).lpNorm<Eigen::Infinity>(), 1e-9 * (1 + dense.maxCoeff()));
}

INSTANTIATE_TEST_SUITE_P(P1P2P3KappaAndHenonHeiles, EachProblem, ::testing::Values(0, 1, 2, 3, 4));

TEST(Problems, SineGordonGridAndInitialData) {
  const Problem p = sine_gordon(32);
  const double dx = 2.0 / 32;
  EXPECT_DOUBLE_EQ(p.M.column[0], 2 / (dx * dx));
  EXPECT_DOUBLE_EQ(p.M.column[31], -1 / (dx * dx));
  EXPECT_DOUBLE_EQ(p.q0[5], M_PI);
  EXPECT_NEAR(p.p0[7], std::sqrt(32.0) * (0.01 + std::sin(2 * M_PI * 8 / 32)), 1e-14);
}

}  // namespace
}  // namespace ex
