// Peers: observed orders on P3, honest force counts, the Gauss stage solver's FFT path.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <erkn/integrator.hpp>
#include <erkn/method.hpp>
#include <set>
#include <unsupported/Eigen/KroneckerProduct>

#include "block_solve.hpp"
#include "problem.hpp"
#include "solver.hpp"
#include "splitting.hpp"

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

// The exact-flow splitting peers: the observed order on sine-Gordon (N = 16, t = 10), where the
// nonlinearity is O(1), matches the order each composition claims (step counts in the asymptotic
// range, errors 1e-4 .. 1e-12); a kick weight moved between two kicks (consistency kept, symmetry
// broken) must lose the order: the negative control.
double splitting_order(const Solver& s, const Problem& p, const Vec& ref) {
  return observed_order(s, p, ref, s.order() == 6 ? 80 : 320);
}

TEST(SplittingPeers, ObservedOrdersOnSineGordon) {
  const Problem p = sine_gordon(16);
  const Vec ref = reference_solution(p, 10, 1e-15).q;
  for (const auto& s : make_splitting_peers())
    EXPECT_NEAR(splitting_order(*s, p, ref), s->order(), 0.15) << s->name();
  Composition broken = blanes_moan_srkn6b();
  broken.kick[1] += 1e-2, broken.kick[2] -= 1e-2;
  EXPECT_LT(splitting_order(*make_splitting(broken), p, ref), 2.5);
}

TEST(SplittingPeers, FsalSavesOneEvaluationPerStep) {
  const Problem p = sine_gordon(16);
  const struct {
    Composition c;
    int evals;
  } expected[] = {{strang(), 1},
                  {blanes_moan_srkn6b(), 6},
                  {blanes_moan_srkn14a(), 14},
                  {aba1064(), 8},
                  {mollified_impulse(), 1}};
  for (const auto& e : expected) {
    EXPECT_EQ(evaluations_per_step(e.c), e.evals) << e.c.name;
    const bool fsal = e.c.kick.front() != 0;
    EXPECT_EQ(make_splitting(e.c)->run(p, 0.1, 10, nullptr).stats.grad_evals,
              10 * e.evals + (fsal ? 1 : 0))
        << e.c.name;
  }
}

// At V = 0 Strang is leapfrog: tr S(0, z) = 2 - z, unstable exactly from z = 4. Every splitting
// peer is stable for small z (the search finds no instability below 0.01).
TEST(SplittingPeers, LinearStabilityLimitAtVZero) {
  EXPECT_NEAR(*make_splitting(strang())->first_unstable_z(), 4.0, 1e-9);
  for (const auto& s : make_splitting_peers()) {
    const auto z = s->first_unstable_z();
    ASSERT_TRUE(z) << s->name();
    EXPECT_GT(*z, 0.01) << s->name();
  }
  EXPECT_FALSE(make_stormer_verlet()->first_unstable_z());  // not a splitting peer: no answer
}

// Without a nonlinearity every exact-flow peer is exact at any step size (here h omega_max ~ 16).
TEST(SplittingPeers, ExactForTheLinearPart) {
  Problem p = sine_gordon(16);
  p.grad_u = [](const Vec& q, Vec& g) { g.setZero(q.size()); };
  const Eigen::MatrixXd m = p.M.dense(16);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(m);
  const Vec w = es.eigenvalues().cwiseMax(0).cwiseSqrt();
  const double t = 2;  // q(t) = cos(t sqrt M) q0 + t sinc(t sqrt M) p0, in M's eigenbasis
  Vec c(16), s(16);
  for (int k = 0; k < 16; ++k)
    c[k] = std::cos(w[k] * t), s[k] = w[k] == 0 ? t : std::sin(w[k] * t) / w[k];
  const Eigen::MatrixXd v = es.eigenvectors();
  const Vec exact =
      v * (c.cwiseProduct(v.transpose() * p.q0) + s.cwiseProduct(v.transpose() * p.p0));
  for (const auto& solver : make_splitting_peers())
    EXPECT_LT((solver->run(p, 1.0, 2, nullptr).q - exact).lpNorm<Eigen::Infinity>(), 1e-12)
        << solver->name();
}

// The charts pair an ERKN method with its RKN limit by Solver::limit_of (registry data, not
// names): with M = 0 (V = 0 throughout) the named ERKN method integrates exactly like the limit.
// Every RKN limit names a different ERKN method (a pairing by stage count alone would not), and
// nothing else names one.
TEST(Peers, EveryRknLimitNamesTheErknMethodItIsTheLimitOf) {
  erkn::System free;  // q'' = -q^3 - q
  free.M = erkn::Stiffness::scalar(0);
  free.gradient = [](const Eigen::VectorXd& q, Eigen::VectorXd& g) {
    g = q.array().cube() + q.array();
  };
  const Eigen::VectorXd q0 = Eigen::VectorXd::Constant(1, 0.8), p0 = Eigen::VectorXd::Zero(1);
  std::set<std::string> named;
  for (const auto& s : make_erkn_solvers()) {
    SCOPED_TRACE(s->name());
    if (s->family() != Family::rkn) {
      EXPECT_EQ(s->limit_of(), "");
      continue;
    }
    ASSERT_NE(s->limit_of(), "");
    EXPECT_TRUE(named.insert(s->limit_of()).second) << s->limit_of() << " named twice";
    const erkn::Method& erkn_method = erkn::Method::by_name(s->limit_of());
    EXPECT_EQ(erkn_method.kind(), erkn::Kind::erkn);
    erkn::Integrator a(erkn_method, free, 0.1, q0, p0),
        b(erkn::Method::by_name(s->name()), free, 0.1, q0, p0);
    a.integrate(5.0);
    b.integrate(5.0);
    EXPECT_LT(std::abs(a.q()[0] - b.q()[0]), 1e-14);
  }
  EXPECT_GE(named.size(), 2u);
}

}  // namespace
}  // namespace ex
