// Peers: observed orders on P3, honest force counts, the Gauss stage solver's FFT path.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <unsupported/Eigen/KroneckerProduct>

#include "block_solve.hpp"
#include "reference.hpp"
#include "solver.hpp"

namespace ex {
namespace {

double observed_order(const Solver& s, const Problem& p, const Vec& ref, long n) {
  const double e1 = (s.run(p, 10.0 / n, n, nullptr).q - ref).lpNorm<Eigen::Infinity>();
  const double e2 = (s.run(p, 5.0 / n, 2 * n, nullptr).q - ref).lpNorm<Eigen::Infinity>();
  return std::log2(e1 / e2);
}

TEST(Peers, ObservedOrdersOnStellarOrbits) {
  const Problem p = stellar_orbits();
  const Vec ref = reference_solution(p, 10, 1e-15).q;
  EXPECT_NEAR(observed_order(*make_stormer_verlet(), p, ref, 400), 2.0, 0.1);
  EXPECT_NEAR(observed_order(*make_mclachlan_sb3a(), p, ref, 200), 4.0, 0.2);
  EXPECT_NEAR(observed_order(*make_mclachlan_sb3a_m4(), p, ref, 200), 4.0, 0.2);
  EXPECT_NEAR(observed_order(*make_gauss2(), p, ref, 200), 4.0, 0.2);
}

TEST(Peers, ForceEvaluationsAreCounted) {
  const Problem p = duffing();
  EXPECT_EQ(make_stormer_verlet()->run(p, 0.01, 100, nullptr).stats.grad_evals, 101);
  EXPECT_EQ(make_mclachlan_sb3a()->run(p, 0.01, 100, nullptr).stats.grad_evals, 600);
  EXPECT_EQ(make_mclachlan_sb3a_m4()->run(p, 0.01, 100, nullptr).stats.grad_evals, 500);
  const RunStats g = make_gauss2()->run(p, 0.01, 100, nullptr).stats;
  EXPECT_EQ(g.grad_evals, 1 + 2 * g.stage_iterations);
  EXPECT_EQ(g.stage_solves, 100);
}

TEST(Peers, SymplecticPeersKeepTheEnergyBounded) {
  const Problem p = stellar_orbits();
  for (const auto& s : {make_stormer_verlet(), make_gauss2()}) {
    const double h0 = p.energy(p.q0, p.p0);
    double worst = 0;
    Observer obs = [&](double, const Vec& q, const Vec& v) {
      worst = std::max(worst, std::abs(p.energy(q, v) - h0));
    };
    s->run(p, 0.1, 10000, &obs);
    EXPECT_LT(worst, 0.05) << s->name();
  }
}

TEST(BlockSolve, FourierPathSolvesTheKroneckerSystem) {
  const Problem p = sine_gordon(16);
  Eigen::Matrix2d a;
  a << 0.3, -0.1, 0.2, 0.4;
  const double h = 0.05;
  BlockSolve block(p.M, 16, h, a);
  Vec x1 = Vec::LinSpaced(16, -1, 2), x2 = Vec::LinSpaced(16, 3, -1);
  Eigen::VectorXd rhs(32);
  rhs << x1, x2;
  block.solve(x1, x2);
  const Eigen::MatrixXd k =
      Eigen::MatrixXd::Identity(32, 32) + h * h * Eigen::kroneckerProduct(a, p.M.dense(16));
  Eigen::VectorXd x(32);
  x << x1, x2;
  EXPECT_LT((k * x - rhs).lpNorm<Eigen::Infinity>(), 1e-12);
}

}  // namespace
}  // namespace ex
