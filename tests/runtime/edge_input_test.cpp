// Inputs at the edges (issue 21): each is refused with an erkn::Error that names it, before any
// state changes, or handled as the documented round-off window says. Every test here failed
// before its fix (silent NaN, a wrong time, a hang, a corrupted state, std::bad_alloc).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>

#include "problems.hpp"
#include "refusals.hpp"

namespace erkn::test {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
const Eigen::Vector3d kQ(0.6, -0.4, 0.3), kP(0.2, 0.5, -0.7);

Integrator running(const char* method = "SERKN2s4", double h = 0.1) {
  Integrator run(Method::by_name(method), polynomial_system(), h, kQ, kP);
  run.step();
  return run;
}

TEST(EdgeInput, GridSpacingWhoseEigenvaluesOverflowIsRefused) {
  // 4 / spacing^2 = inf, and the zero mode's 0 * inf was NaN.
  const std::string message = error_of([] {
    Stiffness::grid({{8, 1e-200, GridAxis::Boundary::periodic}});
  });
  EXPECT_CONTAINS(message, "axis 0 has spacing 1e-200");
  // Negative control: a tiny spacing whose eigenvalues are finite is accepted.
  const Stiffness M = Stiffness::grid({{8, 1e-100, GridAxis::Boundary::periodic}});
  EXPECT_TRUE(M.eigenvalues().allFinite());
}

TEST(EdgeInput, GridTooLargeToAllocateIsAnErknError) {
  const auto huge = [] {
    Stiffness::grid({{1000000, 1.0, GridAxis::Boundary::periodic},
                     {1000000, 1.0, GridAxis::Boundary::periodic}});
  };
  EXPECT_CONTAINS(error_of(huge), "1000000000000 unknowns");  // (was std::bad_alloc)
}

TEST(EdgeInput, CoefficientsRefuseANaNOrNegativePoleTolerance) {
  int checked = 0;
  for (const Method& m : methods_of(Kind::erkn)) {
    if (m.poles().empty()) continue;
    const double P = m.poles()[0];
    for (double tol : {kNaN, -1.0, kInf})
      EXPECT_CONTAINS(error_of([&] { m.at(P, tol); }), "pole_tolerance");
    // Negative controls: a valid tolerance refuses the pole itself, tolerance 0 away from it is
    // accepted (the advisor's use).
    EXPECT_CONTAINS(error_of([&] { m.at(P, 1e-6); }), "singular");
    EXPECT_NO_THROW(m.at(0.5 * P, 0.0));
    ++checked;
  }
  EXPECT_GT(checked, 0);
}

// The step-size check over M's eigenvalues (v = h^2 lambda, h = 1) refuses a v within a relative
// pole_tolerance of a pole and accepts one outside, also below a quarter of the first pole, where
// it decides for all eigenvalues at once (tolerance <= 1/2). Negative control: at tolerance 0.8
// a v of 0.24 P_1 is within it, and is refused.
TEST(EdgeInput, StepSizeCheckBelowTheFirstPoleAgreesWithEachEigenvalues) {
  int checked = 0;
  for (const Method& m : methods_of(Kind::erkn)) {
    if (m.poles().empty()) continue;
    SCOPED_TRACE(std::string(m.name()));
    const double P = m.poles()[0];
    const auto construct = [&](double v, double tolerance) {
      Options o;
      o.pole_tolerance = tolerance;
      const Eigen::VectorXd lambda = Eigen::Vector2d(0.01 * v, v), q0 = Eigen::Vector2d(0.1, 0.2);
      Integrator(m, sine_gordon(Stiffness::diagonal(lambda)), 1.0, q0, q0, o);
    };
    EXPECT_NO_THROW(construct(std::nextafter(0.25 * P, 0.0), 1e-6));
    EXPECT_NO_THROW(construct(std::nextafter(0.25 * P, 0.0), 0.5));
    EXPECT_NO_THROW(construct(0.25 * P, 1e-6));
    EXPECT_CONTAINS(error_of([&] { construct(P * (1 - 0.5e-6), 1e-6); }), "pole");
    EXPECT_CONTAINS(error_of([&] { construct(0.24 * P, 0.8); }), "pole");
    EXPECT_NO_THROW(construct(0.1 * P, 0.8));
    ++checked;
  }
  EXPECT_GT(checked, 0);
}

TEST(EdgeInput, StateAtANonFiniteTimeIsRefused) {
  Integrator run = running();
  const Snapshot before(run);
  Eigen::VectorXd q, p;
  for (double t : {kInf, -kInf, kNaN}) {
    EXPECT_CONTAINS(error_of([&] { run.state_at(t, q, p); }), "not finite");
    before.expect_same(run);
  }
  EXPECT_NO_THROW(run.state_at(run.t() + 0.5 * run.h(), q, p));  // negative control
}

TEST(EdgeInput, AStepThatCannotAdvanceTheTimeIsRefused) {
  for (const Method& m : Method::all()) {
    SCOPED_TRACE(std::string(m.name()));
    Integrator run(m, polynomial_system(), 0.1, kQ, kP);
    run.set_state(kQ, kP, 1e20);  // 0.1 is below the round-off of 1e20
    const Snapshot before(run);
    EXPECT_CONTAINS(error_of([&] { run.step(); }), "round-off");
    before.expect_same(run);
    run.set_state(kQ, kP, 1e6);  // negative control: resolved
    run.step();
    EXPECT_EQ(run.t(), 1e6 + 0.1);
  }
}

// A potential that throws while the energy monitor checks a step: the step did not happen.
TEST(EdgeInput, APotentialThrowingInTheEnergyMonitorKeepsTheStateBeforeTheStep) {
  bool armed = false;
  System s = polynomial_system();
  const auto U = s.potential;
  s.potential = [&armed, U](const Eigen::VectorXd& q) {
    if (armed) throw std::runtime_error("user potential failed");
    return U(q);
  };
  Options o;
  o.energy_tolerance = 0.5;
  for (const Method& m : Method::all()) {
    SCOPED_TRACE(std::string(m.name()));
    armed = false;
    Integrator run(m, s, 0.1, kQ, kP, o), twin(m, s, 0.1, kQ, kP, o);
    run.step(), twin.step();
    const Snapshot before(run);
    armed = true;
    EXPECT_THROW(run.step(), std::runtime_error);
    armed = false;
    before.expect_same(run);
    // ... and continues as if nothing had happened (negative control: the twin never failed; its
    // set_state drops the stage history and summation errors as the rollback does).
    twin.set_state(twin.q(), twin.p(), twin.t());
    run.step(), twin.step();
    EXPECT_EQ(run.q(), twin.q());
    EXPECT_EQ(run.p(), twin.p());
  }
}

TEST(EdgeInput, OutputTimesAreComparedWithinTheRoundOffWindow) {
  const auto none = [](double, const Eigen::VectorXd&, const Eigen::VectorXd&) {};
  Integrator run = running("SERKN2s4", 0.1);
  run.integrate(0.3);  // t() is 0.30000000000000004
  std::vector<double> seen;
  const auto record = [&](double t, const Eigen::VectorXd&, const Eigen::VectorXd&) {
    seen.push_back(t);
  };
  run.integrate(1.0, Eigen::Vector2d(0.3, 0.5), record);
  EXPECT_EQ(seen, std::vector<double>({0.3, 0.5}));
  Integrator fresh(Method::by_name("SERKN2s4"), polynomial_system(), 0.1, kQ, kP);
  EXPECT_NO_THROW(fresh.integrate(0.3, Eigen::VectorXd::Constant(1, 0.1 + 0.2), none));
  // Negative control: a time clearly before t() is refused.
  const Snapshot before(run);
  EXPECT_CONTAINS(error_of([&] { run.integrate(2.0, Eigen::VectorXd::Constant(1, 0.99), none); }),
                  "output time 0");
  before.expect_same(run);
}

// h^2 lambda between the first two poles: a shorter step can land on the first pole.
TEST(EdgeInput, AnOutputTimeWhoseShorterStepHitsAPoleIsRefusedBeforeAnyStep) {
  const auto none = [](double, const Eigen::VectorXd&, const Eigen::VectorXd&) {};
  int checked = 0;
  for (const Method& m : methods_of(Kind::erkn)) {
    if (m.poles().empty() || 1.5 * m.poles()[0] > generated::kPoleSearchMax ||
        m.pole_within(1.5 * m.poles()[0], 1e-2) > 0)
      continue;
    SCOPED_TRACE(std::string(m.name()));
    System s;  // (a weak force: the stages converge at this large h)
    s.M = Stiffness::scalar(1.0);
    s.gradient = [](const Eigen::VectorXd& q, Eigen::VectorXd& g) { g = 1e-3 * q.array().cube(); };
    const double h = std::sqrt(1.5 * m.poles()[0]), shorter = std::sqrt(m.poles()[0]);
    Integrator run(m, s, h, kQ, kP);
    const Snapshot before(run);
    const Eigen::VectorXd times = Eigen::VectorXd::Constant(1, 2 * h + shorter);
    EXPECT_CONTAINS(error_of([&] { run.integrate(3 * h, times, none); }), "pole");
    before.expect_same(run);  // (the two whole steps were taken before)
    // Negative control: a shorter step clear of the pole runs.
    EXPECT_NO_THROW(run.integrate(3 * h, Eigen::VectorXd::Constant(1, 2 * h + 0.5 * h), none));
    ++checked;
  }
  EXPECT_GT(checked, 0);
}

TEST(EdgeInput, TheAdvisorsSearchIsBoundedOrRefused) {
  const Method& m = Method::by_name("SERKN2s4");
  const Eigen::VectorXd lambda = Eigen::VectorXd::LinSpaced(16, 0, 2500);
  const HessianBounds k{-1, 1};
  AdvisorOptions tiny, fine;
  tiny.search_step = 1e-300;
  fine.search_step = 1e-12, fine.max_change = 0.9;
  for (const AdvisorOptions& o : {tiny, fine})
    EXPECT_CONTAINS(error_of([&] { advise_step_size(m, lambda, 0.1, k, o); }), "search_step");
  // Negative control: the defaults give an answer.
  EXPECT_NO_THROW(advise_step_size(m, lambda, 0.1, k));
}

}  // namespace
}  // namespace erkn::test
