// The step-size advisor against runs: on the Fermi-Pasta-Ulam problem (erkn::problems::fpu, stiff
// omega = 50) the step sizes of issue 12 whose long runs blow up or drift are flagged, and runs at
// the suggested step size run clean over 1e5 steps. Plus its refusals and the opt-in check at
// construction.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "problems.hpp"

namespace erkn::test {
namespace {

constexpr double kOmega = kStiffOmega, kPi = std::numbers::pi;
System fpu() { return problems::system(stiff_fpu()); }

// max |H_n - H_0| / |H_0| over n steps (sampled every 50 steps); infinity if the run fails.
// (The blow-up guard is off: this measures how far a flagged h drifts.)
double energy_error(const Method& m, double h, long n) {
  Options unguarded;
  unguarded.blowup_guard = false;
  Integrator run(m, fpu(), h, stiff_fpu().q0, stiff_fpu().p0, unguarded);
  const double H0 = run.energy();
  double worst = 0;
  try {
    for (long k = 1; k <= n; ++k) {
      run.step();
      if (k % 50 == 0) worst = std::max(worst, std::abs(run.energy() - H0) / std::abs(H0));
    }
  } catch (const Error&) {
    return std::numeric_limits<double>::infinity();
  }
  return worst;
}

// "Runs clean" at h: over 1e5 steps the relative energy error is below 0.5 and at most 10 times
// the smaller of the errors at h (1 - 3 %) and h (1 + 3 %): the error the method has at that step
// size off resonance, not a resonance peak (the peaks at the flagged step sizes are 3 to 1e7
// times higher; docs/stability-advisor.md, "Resonances").
// Returns that smaller neighbouring error.
double expect_clean(const Method& m, double h, double error) {
  const double neighbours =
      std::min(energy_error(m, 0.97 * h, 100000), energy_error(m, 1.03 * h, 100000));
  EXPECT_LT(error, 0.5);
  EXPECT_LE(error, 10 * neighbours) << "neighbours " << neighbours;
  return neighbours;
}

// The Hessian range along a pilot run of t = 100 at h omega = 0.5 (hi about 23; at the
// initial state alone it is [0, 12.5], too narrow: the slow springs stretch further later).
HessianBounds pilot_hessian(const Method& m) {
  return hessian_bounds_along(m, fpu(), 0.5 / kOmega, stiff_fpu().q0, stiff_fpu().p0, 10000);
}

// Issue 12's resonant step sizes h omega, for every ERKN method of the registry including the
// explicit (splitting) ones (one test per method and step size, to keep each short): flagged; the
// suggested h runs clean over 1e5 steps and its energy error is at least 3 times smaller than the
// flagged h's. Prints a table row (docs/stability-advisor.md).
void expect_predicted(const Method& m, double h_omega) {
  const double h = h_omega / kOmega;
  const Eigen::VectorXd lambda = fpu().M.eigenvalues();
  const HessianBounds hessian = pilot_hessian(m);
  const StepSizeAdvice advice = advise_step_size(m, lambda, h, hessian);
  ASSERT_FALSE(advice.safe()) << advice.report(m);
  ASSERT_TRUE(std::isfinite(advice.suggested_h)) << advice.report(m);
  EXPECT_TRUE(advise_step_size(m, lambda, advice.suggested_h, hessian).safe());
  const double flagged = energy_error(m, h, 100000);
  const double suggested = energy_error(m, advice.suggested_h, 100000);
  const double neighbours = expect_clean(m, advice.suggested_h, suggested);
  EXPECT_GT(flagged, 3 * suggested) << advice.report(m);
  std::printf("| %s | %.4g | %.2e | %.4f | %.2e | %.2e |\n", std::string(m.name()).c_str(),
              h_omega / kPi, flagged, advice.suggested_h * kOmega / kPi, suggested, neighbours);
}

class AdvisorFpu : public ::testing::TestWithParam<size_t> {
 protected:
  const Method& method() const {
    static const std::vector<Method> all = methods_of(Kind::erkn);
    return all[GetParam()];
  }
};

TEST_P(AdvisorFpu, PredictsTheBlowUpJustBelowPi) { expect_predicted(method(), 0.999 * kPi); }
TEST_P(AdvisorFpu, PredictsTheResonanceAtPi) { expect_predicted(method(), kPi); }
TEST_P(AdvisorFpu, PredictsTheResonanceAt3Pi) { expect_predicted(method(), 3 * kPi); }
TEST_P(AdvisorFpu, PredictsTheDriftJustAbove2Pi) { expect_predicted(method(), 2 * kPi * 1.001); }

INSTANTIATE_TEST_SUITE_P(Registry, AdvisorFpu,
                         ::testing::Range(size_t(0), methods_of(Kind::erkn).size()),
                         [](const ::testing::TestParamInfo<size_t>& info) {
                           return std::string(methods_of(Kind::erkn)[info.param].id_name());
                         });

// Negative control: h omega = 1 is far from every k pi and not flagged; its run is accurate.
TEST(Advisor, AcceptsANonResonantStepAndItsRunIsAccurate) {
  const Eigen::VectorXd &q = stiff_fpu().q0, &p = stiff_fpu().p0;
  for (const Method& m : methods_of(Kind::erkn)) {
    SCOPED_TRACE(std::string(m.name()));
    const StepSizeAdvice advice = advise_step_size(m, fpu(), 1 / kOmega, q, p);
    EXPECT_TRUE(advice.safe()) << advice.report(m);
    EXPECT_EQ(advice.suggested_h, 1 / kOmega);
    EXPECT_LT(energy_error(m, 1 / kOmega, 5000), 0.02);
  }
}

// The band is the slow phase h sqrt(hi) (plus the tongue width from S): with a zero Hessian (a
// linear problem, which ERKN methods integrate exactly) nothing resonates even next to pi; with
// hi > 0, h sqrt(lambda) = pi + 0.9 h sqrt(hi) lies in the parametric tongue (harmonic r = 2).
TEST(Advisor, ResonanceBandIsTheSlowPhasePerStep) {
  for (const Method& m : methods_of(Kind::erkn)) {
    SCOPED_TRACE(std::string(m.name()));
    const Eigen::VectorXd lambda = Eigen::VectorXd::Constant(1, kOmega * kOmega);
    EXPECT_TRUE(advise_step_size(m, lambda, kPi * (1 + 1e-6) / kOmega, {0, 0}).safe());
    const double hi = 12,
                 h = kPi / (kOmega - 0.9 * std::sqrt(hi));  // h omega - pi = 0.9 h sqrt(hi)
    const StepSizeAdvice a = advise_step_size(m, lambda, h, {0, hi});
    ASSERT_EQ(a.findings.size(), 1u) << a.report(m);
    EXPECT_EQ(a.findings[0].hazard, Hazard::resonance);
    EXPECT_EQ(a.findings[0].harmonic, 2);
  }
}

TEST(Advisor, HessianRangeAlongAPilotRunContainsTheInitialOne) {
  const Method& m = Method::all()[0];
  const HessianBounds at = hessian_bounds_at(fpu(), stiff_fpu().q0);
  const HessianBounds along =
      hessian_bounds_along(m, fpu(), 0.5 / kOmega, stiff_fpu().q0, stiff_fpu().p0, 1000);
  EXPECT_LE(along.lo, at.lo);
  EXPECT_GT(along.hi, 1.2 * at.hi);  // FPU's slow springs stretch beyond the initial state
  const HessianBounds none =
      hessian_bounds_along(m, fpu(), 0.5 / kOmega, stiff_fpu().q0, stiff_fpu().p0, 0);
  EXPECT_EQ(none.hi, at.hi);
  EXPECT_THROW(hessian_bounds_along(m, fpu(), 0.5 / kOmega, stiff_fpu().q0, stiff_fpu().p0, -1),
               Error);
}

TEST(Advisor, FlagsThePolesOfEveryMethod) {
  for (const Method& m : Method::all()) {
    SCOPED_TRACE(std::string(m.name()));
    for (double P : m.poles()) {
      const StepSizeAdvice a = advise_step_size(m, Eigen::VectorXd::Constant(1, 4.0),
                                                std::sqrt(P * (1 + 1e-4) / 4), {0, 0});
      ASSERT_EQ(a.findings.size(), 1u);
      EXPECT_EQ(a.findings[0].hazard, Hazard::pole);
      EXPECT_EQ(a.findings[0].pole, P);
    }
  }
}

// A strongly negative Hessian (lambda + kappa = -49: the test equation itself grows like
// e^{7 t}): every method grows with it, which is the equation's growth, reported as information
// and not flagged. Negative control: the same methods at lambda + kappa >= 0 (V = 0, z > 0, where
// the equation is bounded) with |tr S| > 2 are flagged as unstable.
TEST(Advisor, SeparatesTheEquationsGrowthFromTheMethods) {
  int method_unstable = 0;
  for (const Method& m : Method::all()) {
    SCOPED_TRACE(std::string(m.name()));
    const StepSizeAdvice a =
        advise_step_size(m, Eigen::VectorXd::Constant(1, 1.0), 0.1, {-50, -50});
    EXPECT_TRUE(a.safe()) << a.report(m);
    ASSERT_EQ(a.equation.size(), 1u);
    EXPECT_EQ(a.equation[0].hazard, Hazard::equation);
    EXPECT_NEAR(a.equation[0].rate, 7.0, 1e-12);
    EXPECT_GT(std::abs(a.equation[0].trace), 2.0);  // (the method does grow)
    EXPECT_NE(a.report(m).find("differential equation itself grows"), std::string::npos);
    // The first z in (0, 40] where the method is unstable on the bounded equation y'' = -kappa y.
    const Coefficients c = m.at(0.0, 0.0);
    for (double z = 0.01; z <= 40; z += 0.01) {
      if (std::abs(stability_matrix(m, c, 0.0, z).trace()) <= 2 + 1e-6) continue;
      const StepSizeAdvice b =
          advise_step_size(m, Eigen::VectorXd::Zero(1), 1.0, {z, z});  // (h = 1: z = kappa)
      EXPECT_FALSE(b.safe()) << "z = " << z;
      if (!b.safe()) EXPECT_EQ(b.findings[0].hazard, Hazard::unstable);
      EXPECT_TRUE(b.equation.empty());
      ++method_unstable;
      break;
    }
  }
  EXPECT_GT(method_unstable, 0);  // (the control has cases)
}

TEST(Advisor, RefusesInvalidInput) {
  const Method& m = Method::all()[0];
  const Eigen::VectorXd lambda = Eigen::VectorXd::Constant(2, 1.0);
  EXPECT_THROW(advise_step_size(m, lambda, 0.0, {0, 1}), Error);
  EXPECT_THROW(advise_step_size(m, lambda, std::nan(""), {0, 1}), Error);
  EXPECT_THROW(advise_step_size(m, lambda, 0.1, {1, 0}), Error);
  EXPECT_THROW(advise_step_size(m, lambda, 0.1, {0, INFINITY}), Error);
  EXPECT_THROW(advise_step_size(m, Eigen::VectorXd::Constant(1, -1.0), 0.1, {0, 1}), Error);
  AdvisorOptions o;
  o.z_samples = 1;
  EXPECT_THROW(advise_step_size(m, lambda, 0.1, {0, 1}, o), Error);
  EXPECT_NO_THROW(advise_step_size(m, lambda, 0.1, {0, 1}));
}

// Options::check_stability refuses exactly the h that advise_step_size(method, system, h, q, p)
// flags (its trial run included), with that report, at construction and at set_step_size (which
// keeps h); off by default. At h omega = pi the low-order methods are refused (their runs drift
// beyond the limit), the accurate ones accepted (the resonance is information): both occur.
TEST(Advisor, OptInCheckAtConstructionAndStepSizeChange) {
  const Eigen::VectorXd &q = stiff_fpu().q0, &p = stiff_fpu().p0;
  Options checked;
  checked.check_stability = true;
  int refused = 0, accepted = 0;
  for (const Method& m : methods_of(Kind::erkn)) {
    SCOPED_TRACE(std::string(m.name()));
    const double h = kPi / kOmega;
    const StepSizeAdvice advice = advise_step_size(m, fpu(), h, q, p);
    try {
      Integrator(m, fpu(), h, q, p, checked);
      EXPECT_TRUE(advice.safe()) << advice.report(m);
      ++accepted;
    } catch (const Error& e) {
      EXPECT_FALSE(advice.safe());
      EXPECT_NE(std::string(e.what()).find(advice.report(m)), std::string::npos) << e.what();
      ++refused;
    }
    EXPECT_NO_THROW(Integrator(m, fpu(), h, q, p));  // off by default
    Integrator run(m, fpu(), 1 / kOmega, q, p, checked);
    if (advice.safe())
      EXPECT_NO_THROW(run.set_step_size(h));
    else
      EXPECT_THROW(run.set_step_size(h), Error);
    EXPECT_EQ(run.h(), advice.safe() ? h : 1 / kOmega);
  }
  EXPECT_GT(refused, 0);
  EXPECT_GT(accepted, 0);
}

}  // namespace
}  // namespace erkn::test
