// The step-size advisor with the state (advise_step_size(method, system, h, q0, p0)): the mode
// energies it reads (erkn::mode_energies, every structure of M), no false alarm on docs/python.md's
// sine-Gordon example (the differential equation grows at u = pi, the method does not) and on a
// 1-D Dirichlet wave grid with smooth data (a dense spectrum always has some eigenvalue in a
// resonance band; those short waves hold no energy), and the alarm where such a mode is excited.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "problems.hpp"

namespace erkn::test {
namespace {

using B = GridAxis::Boundary;
constexpr double kPi = std::numbers::pi;

// E_2 = 1/2 |p|^2 + 1/2 q'Mq.
double linear_energy(const Stiffness& M, const Eigen::VectorXd& q, const Eigen::VectorXd& p) {
  return 0.5 * p.squaredNorm() + 0.5 * q.dot(M.to_dense(q.size()) * q);
}

Eigen::VectorXd random_vector(Eigen::Index d, unsigned seed) {
  std::srand(seed);
  return Eigen::VectorXd::Random(d);
}

TEST(ModeEnergies, SumToTheLinearEnergyForEveryStructure) {
  Eigen::VectorXd col = Eigen::VectorXd::Zero(100);
  col[0] = 2, col[1] = col[99] = -1;
  const std::vector<std::pair<Stiffness, Eigen::Index>> cases = {
      {Stiffness::scalar(2.5), 3},
      {Stiffness::diagonal(Eigen::Vector3d(0, 1, 4)), 3},
      {Stiffness::dense(rotated({1.0, 2.5, 6.0})), 3},
      {Stiffness::circulant((Eigen::VectorXd(7) << 2, -1, 0, 0, 0, 0, -1).finished()), 7},
      {Stiffness::circulant(col), 100},
      {Stiffness::grid({{9, 0.1, B::dirichlet}}), 9},
      {Stiffness::grid({{8, 0.1, B::periodic}, {5, 0.2, B::neumann}}, 1.5), 40},
      {Stiffness::grid({{6, 0.1, B::periodic}, {7, 0.2, B::periodic}}), 42}};
  for (size_t c = 0; c < cases.size(); ++c) {
    SCOPED_TRACE(c);
    const auto& [M, d] = cases[c];
    const Eigen::VectorXd q = random_vector(d, 1 + c), p = random_vector(d, 100 + c);
    const Eigen::VectorXd e = mode_energies(M, q, p);
    ASSERT_EQ(e.size(), M.eigenvalues().size());
    EXPECT_GE(e.minCoeff(), -1e-14);
    EXPECT_NEAR(e.sum(), linear_energy(M, q, p), 1e-12 * linear_energy(M, q, p));
  }
}

// One Dirichlet sine mode sin(k pi x) puts all its energy at eigenvalue index k - 1 (and the
// physical p counts, too); a wrong size is refused.
TEST(ModeEnergies, PutAModesEnergyAtItsEigenvalue) {
  const int n = 31, k = 5;
  const Stiffness M = Stiffness::grid({{n, 1.0 / (n + 1), B::dirichlet}});
  Eigen::VectorXd q(n), p = Eigen::VectorXd::Zero(n);
  for (int i = 0; i < n; ++i) q[i] = std::sin(kPi * k * (i + 1) / (n + 1));
  Eigen::VectorXd e = mode_energies(M, q, p);
  EXPECT_NEAR(e[k - 1], linear_energy(M, q, p), 1e-10 * e[k - 1]);
  EXPECT_LT(e.sum() - e[k - 1], 1e-20 * e[k - 1]);
  e = mode_energies(M, p, q);  // (as a velocity)
  EXPECT_NEAR(e[k - 1], 0.5 * q.squaredNorm(), 1e-12);
  EXPECT_THROW(mode_energies(M, q.head(n - 1), p.head(n - 1)), Error);
  EXPECT_THROW(mode_energies(M, q, p.head(n - 1)), Error);
  p[0] = NAN;
  EXPECT_THROW(mode_energies(M, q, p), Error);
}

// max |H_n - H_0| / |H_0| over `steps` steps, every 10 steps (no guard).
double energy_error(const Method& m, const System& s, double h, const Eigen::VectorXd& q0,
                    const Eigen::VectorXd& p0, long steps) {
  Options unguarded;
  unguarded.blowup_guard = false;
  Integrator run(m, s, h, q0, p0, unguarded);
  const double H0 = run.energy();
  double worst = 0;
  for (long k = 1; k <= steps; ++k) {
    run.step();
    if (k % 10 == 0) worst = std::max(worst, std::abs(run.energy() - H0) / std::abs(H0));
  }
  return worst;
}

// The sine-Gordon example of docs/python.md (P1) at the h = 0.025 and h = 0.1: M + Hessian
// of U has the direction lambda = 0, kappa = -1 (u = pi is the top of the pendulum), which the
// advisor reports as the equation's growth, rate 1, and flags nothing; check_stability accepts the
// construction. The runs keep the energy (5e3 steps). Negative control: a Hessian range with
// kappa >= 0 there reports no growth.
TEST(AdvisorState, SineGordonsOwnGrowthIsNoAlarm) {
  const problems::Problem p1 = problems::sine_gordon(32);
  const System s = problems::system(p1);
  Options checked;
  checked.check_stability = true;
  for (const Method& m : methods_of(Kind::erkn))
    for (double h : {0.025, 0.1}) {
      SCOPED_TRACE(std::string(m.name()) + " h = " + std::to_string(h));
      const StepSizeAdvice a = advise_step_size(m, s, h, p1.q0, p1.p0);
      if (a.findings.size() == 1 && a.findings[0].hazard == Hazard::pole) continue;
      EXPECT_TRUE(a.safe()) << a.report(m);
      ASSERT_EQ(a.equation.size(), 1u) << a.report(m);
      EXPECT_EQ(a.equation[0].lambda, 0.0);
      EXPECT_NEAR(a.equation[0].rate, 1.0, 1e-6);
      EXPECT_NO_THROW(Integrator(m, s, h, p1.q0, p1.p0, checked));
      EXPECT_LT(energy_error(m, s, h, p1.q0, p1.p0, 5000), 1e-2);
      const StepSizeAdvice bounded =
          advise_step_size(m, s.M.eigenvalues(), h, {0, 1}, {}, mode_energies(s.M, p1.q0, p1.p0));
      EXPECT_TRUE(bounded.equation.empty());
    }
}

// u_tt = u_xx - u^3 on (0, 1), Dirichlet, n = 255 interior points, u0 = sin(pi x), h = 0.01:
// h sqrt(lambda) runs over (0, 5.1), so some short wave always sits near pi or 4 pi / 3.
struct WaveGrid {
  System s;
  Eigen::VectorXd q0, p0;
  explicit WaveGrid(int excite = 0, double amplitude = 0) {
    const int n = 255;
    const double dx = 1.0 / (n + 1);
    s.M = Stiffness::grid({{n, dx, B::dirichlet}});
    s.gradient = [](const Eigen::VectorXd& q, Eigen::VectorXd& g) { g = q.array().cube(); };
    s.hessian_vector_product = [](const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                  Eigen::VectorXd& hv) { hv = 3 * q.array().square() * v.array(); };
    s.potential = [](const Eigen::VectorXd& q) { return 0.25 * q.array().pow(4).sum(); };
    q0.resize(n), p0 = Eigen::VectorXd::Zero(n);
    for (int i = 0; i < n; ++i)
      q0[i] = std::sin(kPi * (i + 1) * dx) + amplitude * std::sin(kPi * excite * (i + 1) * dx);
  }
};

// No false alarm on smooth data, and the runs keep the energy (2000 steps); the same advice
// without the state (every mode counted as excited) flags short waves: the mode energies are
// what clears them. With the resonant short wave excited (1 % amplitude) the advisor reports it
// (a finding, or a note when the trial run of the 2000 steps keeps the energy within the limit:
// flagged exactly when that run's error reaches it) and that run's energy error is >= 10 times
// the smooth run's.
TEST(AdvisorState, WaveGridFlagsOnlyExcitedResonantModes) {
  const double h = 0.01;
  const WaveGrid smooth;
  for (const Method& m : methods_of(Kind::erkn)) {
    SCOPED_TRACE(std::string(m.name()));
    AdvisorOptions verdict_only;  // (no search for a suggested h over the 255 eigenvalues)
    verdict_only.max_change = 0;
    verdict_only.steps = verdict_only.trial_steps = 2000;  // (the trial is the whole run)
    const StepSizeAdvice a = advise_step_size(m, smooth.s, h, smooth.q0, smooth.p0, verdict_only);
    if (!a.safe() && a.findings[0].hazard == Hazard::pole) continue;
    EXPECT_TRUE(a.safe()) << a.report(m);
    EXPECT_TRUE(a.notes.empty()) << a.report(m);
    const StepSizeAdvice blind =
        advise_step_size(m, smooth.s.M.eigenvalues(), h, a.hessian, verdict_only);
    ASSERT_FALSE(blind.safe());
    const AdvisorFinding& f = blind.findings[0];
    EXPECT_EQ(f.hazard, Hazard::resonance);
    const WaveGrid excited(int(f.index) + 1, 0.01);
    const StepSizeAdvice b =
        advise_step_size(m, excited.s, h, excited.q0, excited.p0, verdict_only);
    const std::vector<AdvisorFinding>& reported = b.safe() ? b.notes : b.findings;
    ASSERT_FALSE(reported.empty()) << b.report(m);
    EXPECT_EQ(reported[0].index, f.index);
    const double clean = energy_error(m, smooth.s, h, smooth.q0, smooth.p0, 2000);
    const double driven = energy_error(m, excited.s, h, excited.q0, excited.p0, 2000);
    EXPECT_LT(clean, 1e-4);
    EXPECT_GT(driven, 10 * clean);
    ASSERT_TRUE(b.trial.explained);  // (the resonance explains the trial's error)
    EXPECT_EQ(b.trial.limit,
              verdict_only.energy_tolerance / (b.trial.saturated ? verdict_only.saturated_margin
                                                                 : verdict_only.explained_margin));
    EXPECT_EQ(b.safe(), b.trial.error < b.trial.limit);
    std::printf("%s: smooth %.2e, resonant mode excited %.2e\n", std::string(m.name()).c_str(),
                clean, driven);
  }
}

}  // namespace
}  // namespace erkn::test
