// Reliability (issue 12): every Options field validated, no silent non-finite state, the energy
// monitor, the registry's bounds, and a failed step that counts nothing.
#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <regex>

#include "problems.hpp"
#include "refusals.hpp"

namespace erkn::test {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
const Eigen::Vector3d kQ(0.6, -0.4, 0.3), kP(0.2, 0.5, -0.7);

const Method& method() { return Method::by_name("SERKN2s4"); }

TEST(Reliability, EveryOptionsFieldIsValidated) {
  struct Case {
    const char* field;
    std::function<void(Options&)> set;
  };
  const std::vector<Case> cases = {
      {"tolerance", [](Options& o) { o.tolerance = -1e-14; }},
      {"tolerance", [](Options& o) { o.tolerance = kNaN; }},
      {"roundoff_level", [](Options& o) { o.roundoff_level = -1e-12; }},
      {"roundoff_level", [](Options& o) { o.roundoff_level = kInf; }},
      {"max_fixed_point_iterations", [](Options& o) { o.max_fixed_point_iterations = 0; }},
      {"max_fixed_point_iterations", [](Options& o) { o.max_fixed_point_iterations = -3; }},
      {"max_theta", [](Options& o) { o.max_theta = 1; }},
      {"max_theta", [](Options& o) { o.max_theta = kNaN; }},
      {"max_newton_iterations", [](Options& o) { o.max_newton_iterations = 0; }},
      {"pole_tolerance", [](Options& o) { o.pole_tolerance = kNaN; }},
      {"pole_tolerance", [](Options& o) { o.pole_tolerance = -1e-6; }},
      {"pole_tolerance", [](Options& o) { o.pole_tolerance = 0; }},
      {"energy_tolerance", [](Options& o) { o.energy_tolerance = -1; }},
      {"energy_tolerance", [](Options& o) { o.energy_tolerance = kNaN; }},
  };
  for (const Case& c : cases) {
    Options o;
    c.set(o);
    const std::string message =
        error_of([&] { Integrator(method(), polynomial_system(), 0.1, kQ, kP, o); });
    EXPECT_CONTAINS(message, std::string("Options::") + c.field);
  }
  // Negative control: the defaults and values at the edges of the ranges are accepted.
  Options edge;
  edge.max_fixed_point_iterations = 1;
  edge.max_newton_iterations = 1;
  edge.energy_tolerance = 0.5;
  EXPECT_NO_THROW(Integrator(method(), polynomial_system(), 0.1, kQ, kP, edge));
  EXPECT_NO_THROW(Integrator(method(), polynomial_system(), 0.1, kQ, kP));
}

// With pole_tolerance = NaN the pole test `|v - P| <= tol * P` is false everywhere: such an
// Options must be refused before h (exactly on a pole) is looked at.
TEST(Reliability, NaNPoleToleranceCannotSwitchPoleRefusalOff) {
  for (const Method& m : methods_of(Kind::erkn)) {
    if (m.poles().empty()) continue;
    System s = polynomial_system();
    s.M = Stiffness::scalar(1.0);
    const double h_on_pole = std::sqrt(m.poles()[0]);
    for (double tol : {kNaN, -1.0}) {
      Options o;
      o.pole_tolerance = tol;
      EXPECT_CONTAINS(error_of([&] { Integrator(m, s, h_on_pole, kQ, kP, o); }), "pole_tolerance");
    }
    EXPECT_CONTAINS(error_of([&] { Integrator(m, s, h_on_pole, kQ, kP); }), "of the pole");
  }
}

TEST(Reliability, SetStateKeepsTheDimensionOfAScalarM) {
  System s = polynomial_system();
  s.M = Stiffness::scalar(2.0);  // fits any dimension, the integrator only its own
  Integrator run(method(), s, 0.1, kQ, kP);
  run.step();
  const Eigen::VectorXd q = run.q();
  const std::string message =
      error_of([&] { run.set_state(Eigen::Vector2d(1, 2), Eigen::Vector2d(3, 4), 0); });
  EXPECT_CONTAINS(message, "dimension mismatch");
  EXPECT_CONTAINS(message, "the new q has size 2");
  EXPECT_EQ(run.q(), q);
  run.set_state(kQ, kP, 0);  // negative control: its own dimension
  run.step();
  EXPECT_EQ(run.q().size(), 3);
}

TEST(Reliability, MethodIdOutsideTheRegistry) {
  EXPECT_CONTAINS(error_of([] { Method::get(MethodId(99)); }), "unknown method id 99");
  EXPECT_CONTAINS(error_of([] { Method::get(MethodId(-1)); }), "unknown method id -1");
  for (const Method& m : Method::all()) EXPECT_EQ(Method::get(m.id()).name(), m.name());
}

TEST(Reliability, FailedStepCountsNothing) {
  for (const Method& m : Method::all()) {  // (explicit methods have their own stepper)
    SCOPED_TRACE(std::string(m.name()));
    System s = polynomial_system();
    bool poison = false;
    const auto good = s.gradient;
    s.gradient = [&](const Eigen::VectorXd& q, Eigen::VectorXd& g) {
      good(q, g);
      if (poison) g[0] = kNaN;
    };
    Options o;
    o.max_fixed_point_iterations = 3;  // so a failing stage also goes through Newton
    Integrator run(m, s, 0.1, kQ, kP, o);
    run.step();
    const Statistics before = run.statistics();
    EXPECT_GT(before.gradient_evaluations, 0);
    poison = true;
    EXPECT_THROW(run.step(), Error);
    const Statistics& after = run.statistics();
    EXPECT_EQ(after.steps, before.steps);
    EXPECT_EQ(after.gradient_evaluations, before.gradient_evaluations);
    EXPECT_EQ(after.stage_iterations, before.stage_iterations);
    EXPECT_EQ(after.newton_fallbacks, before.newton_fallbacks);
    EXPECT_EQ(after.hessian_evaluations, before.hessian_evaluations);
    poison = false;  // negative control: the next step counts
    run.step();
    EXPECT_EQ(run.statistics().steps, before.steps + 1);
    EXPECT_GT(run.statistics().gradient_evaluations, before.gradient_evaluations);
  }
}

// A force so large that q_{n+1} overflows: an error naming the step, the state before it kept.
TEST(Reliability, NonFiniteResultIsAnErrorNamingTheStep) {
  for (const Method& m : Method::all()) {
    SCOPED_TRACE(std::string(m.name()));
    System s;
    s.M = Stiffness::scalar(1.0);
    bool huge = false;
    s.gradient = [&](const Eigen::VectorXd& q, Eigen::VectorXd& g) {
      g.setConstant(huge ? std::numeric_limits<double>::max() : 0.0);
      g += 0 * q;
    };
    s.hessian_vector_product = [](const Eigen::VectorXd&, const Eigen::VectorXd& v,
                                  Eigen::VectorXd& hv) { hv.setZero(v.size()); };
    Integrator run(m, s, 1.0, kQ, kP);
    run.step();
    const Eigen::VectorXd q = run.q(), p = run.p();
    huge = true;
    std::string message = error_of([&] {
      for (int n = 0; n < 4; ++n) run.step();  // (overflows at once for most methods)
    });
    // (A processed method's kernel can stay finite where pi, which kicks harder, overflows:
    // then the state cannot be shown, and q() is the error.)
    if (message.empty() && m.is_processed()) message = error_of([&] { run.q(); });
    // (Depending on the method the overflow shows in q_{n+1}, in a stage, or in Newton's
    // residual; each names the step.)
    EXPECT_TRUE(std::regex_search(message, std::regex("step [0-9]+.*(finite|residual inf)")))
        << message;
    if (message.find("the processor pi of") != std::string::npos) continue;
    EXPECT_TRUE(run.q().allFinite());
    EXPECT_TRUE(run.p().allFinite());
  }
}

// r_i overflows while U = 0 makes the gradient finite everywhere: the stage itself is caught.
TEST(Reliability, NonFiniteStageIsAnErrorNamingTheStep) {
  for (const Method& m : methods_of(Kind::erkn)) {
    SCOPED_TRACE(std::string(m.name()));
    System s;
    s.M = Stiffness::scalar(1.0);
    s.gradient = [](const Eigen::VectorXd&, Eigen::VectorXd& g) { g.setZero(); };
    s.hessian_vector_product = [](const Eigen::VectorXd&, const Eigen::VectorXd& v,
                                  Eigen::VectorXd& hv) { hv.setZero(v.size()); };
    const Eigen::VectorXd big = Eigen::VectorXd::Constant(2, 1.5e308);
    if (m.is_processed()) {  // (pi^-1 runs at construction: the state is refused there)
      const std::string message = error_of([&] { Integrator run(m, s, 1.0, big, big); });
      EXPECT_CONTAINS(message, "the processor pi^-1 of");
      EXPECT_CONTAINS(message, "not finite");
      EXPECT_NO_THROW(Integrator(m, s, 1.0, big / 10, big / 10).step());
      continue;
    }
    Integrator run(m, s, 1.0, big, big);
    const std::string message = error_of([&] { run.step(); });
    EXPECT_CONTAINS(message, "step 1");
    EXPECT_CONTAINS(message, "not finite");
    EXPECT_EQ(run.q(), big);
    // Negative control: the same at a tenth of the size steps fine.
    Integrator small(m, s, 1.0, big / 10, big / 10);
    EXPECT_NO_THROW(small.step());
  }
}

TEST(Reliability, EnergyMonitorNamesTheStepAndTheDrift) {
  for (const Method& m : Method::all()) {
    SCOPED_TRACE(std::string(m.name()));
    // h = 0.3 on the polynomial system: |H_n - H_0| / |H_0| is ~1e-4 .. 1e-2 within 50 steps.
    Options o;
    o.energy_tolerance = 1e-9;
    Integrator watched(m, polynomial_system(), 0.3, kQ, kP, o);
    Integrator twin(m, polynomial_system(), 0.3, kQ, kP);
    long failed_at = 0;
    std::string message;
    for (long n = 1; n <= 50 && message.empty(); ++n) {
      message = error_of([&] { watched.step(); });
      if (message.empty()) twin.step();
      failed_at = n;
    }
    ASSERT_FALSE(message.empty()) << "no drift above 1e-9 in 50 steps";
    EXPECT_CONTAINS(message, "energy monitor: step " + std::to_string(failed_at));
    EXPECT_CONTAINS(message, "> Options::energy_tolerance = 1e-09");
    EXPECT_EQ(watched.q(), twin.q());  // the state before the failed step
    EXPECT_EQ(watched.p(), twin.p());
    EXPECT_EQ(watched.t(), twin.t());
    // Negative control: a loose tolerance lets the same run through.
    o.energy_tolerance = 0.5;
    Integrator loose(m, polynomial_system(), 0.3, kQ, kP, o);
    EXPECT_NO_THROW(for (int n = 0; n < 50; ++n) loose.step());
  }
}

TEST(Reliability, EnergyMonitorNeedsAPotential) {
  System s = polynomial_system();
  s.potential = nullptr;
  Options o;
  o.energy_tolerance = 1e-6;
  EXPECT_CONTAINS(error_of([&] { Integrator(method(), s, 0.1, kQ, kP, o); }),
                  "energy_tolerance (the energy monitor) needs System::potential");
}

}  // namespace
}  // namespace erkn::test
