// Every bad input is an erkn::Error with a message that names the problem, and changes nothing.
#include <gtest/gtest.h>

#include <limits>

#include "problems.hpp"

namespace erkn::test {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// Runs f, which must throw erkn::Error containing every one of `parts`.
template <class F>
void expect_error(F&& f, std::initializer_list<const char*> parts) {
  try {
    f();
    ADD_FAILURE() << "no erkn::Error thrown";
  } catch (const Error& e) {
    for (const char* part : parts)
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos)
          << "message '" << e.what() << "' lacks '" << part << "'";
  }
}

// A running integrator and a snapshot of everything a failed call must leave alone.
struct Fixture {
  Integrator run{Method::by_name("SERKN2s4"), polynomial_system(), 0.1,
                 Eigen::Vector3d(0.6, -0.4, 0.3), Eigen::Vector3d(0.2, 0.5, -0.7)};
  Eigen::VectorXd q, p;
  double t, h;
  long steps;
  Fixture() {
    run.step();
    q = run.q(), p = run.p(), t = run.t(), h = run.h(), steps = run.statistics().steps;
  }
  void expect_unchanged() const {
    EXPECT_EQ(run.q(), q);
    EXPECT_EQ(run.p(), p);
    EXPECT_EQ(run.t(), t);
    EXPECT_EQ(run.h(), h);
    EXPECT_EQ(run.statistics().steps, steps);
  }
};

const Eigen::Vector3d kQ(0.6, -0.4, 0.3), kP(0.2, 0.5, -0.7);
// A function, not a global: the registry is not initialised before this file's globals.
const Method& method() { return Method::by_name("SERKN2s4"); }

TEST(BadInput, DimensionMismatchBetweenMAndQ) {
  expect_error(
      [] {
        Integrator(method(), polynomial_system(), 0.1, Eigen::Vector2d(1, 2),
                   Eigen::Vector2d(1, 2));
      },
      {"dimension mismatch", "M is 3x3", "q has size 2"});
}

TEST(BadInput, DimensionMismatchBetweenQAndP) {
  expect_error([] { Integrator(method(), polynomial_system(), 0.1, kQ, Eigen::Vector2d(1, 2)); },
               {"dimension mismatch", "q has size 3", "p has size 2"});
  Fixture f;
  expect_error([&] { f.run.set_state(kQ, Eigen::Vector2d(1, 2), 0); }, {"p has size 2"});
  f.expect_unchanged();
}

TEST(BadInput, GradientOfTheWrongSize) {
  System s = polynomial_system();
  s.gradient = [](const Eigen::VectorXd&, Eigen::VectorXd& g) { g = Eigen::VectorXd::Zero(2); };
  Integrator run(method(), s, 0.1, kQ, kP);
  expect_error([&] { run.step(); },
               {"gradient callback returned a vector of size 2", "size 3", "unchanged"});
  EXPECT_EQ(run.q(), Eigen::VectorXd(kQ));
  EXPECT_EQ(run.p(), Eigen::VectorXd(kP));
  EXPECT_EQ(run.t(), 0.0);
}

TEST(BadInput, NonFiniteQOrP) {
  expect_error(
      [] { Integrator(method(), polynomial_system(), 0.1, Eigen::Vector3d(0, kNaN, 0), kP); },
      {"q[1]", "not finite"});
  expect_error(
      [] { Integrator(method(), polynomial_system(), 0.1, kQ, Eigen::Vector3d(0, 0, kInf)); },
      {"p[2]", "not finite"});
  Fixture f;
  expect_error([&] { f.run.set_state(Eigen::Vector3d(kNaN, 0, 0), kP, 0); },
               {"q[0]", "not finite"});
  f.expect_unchanged();
}

TEST(BadInput, NonFiniteOrNonPositiveStepSize) {
  for (double h : {0.0, -0.1, kNaN, kInf}) {
    expect_error([h] { Integrator(method(), polynomial_system(), h, kQ, kP); },
                 {"step size h must be finite and > 0"});
    Fixture f;
    expect_error([&] { f.run.set_step_size(h); }, {"step size h must be finite and > 0"});
    f.expect_unchanged();
  }
}

TEST(BadInput, NonFiniteM) {
  expect_error([] { Stiffness::scalar(kNaN); }, {"omega2", "not finite"});
  expect_error([] { Stiffness::diagonal(Eigen::Vector2d(1, kInf)); },
               {"diagonal M", "non-finite", "(1, 0)"});
  expect_error([] { Stiffness::circulant(Eigen::Vector3d(2, kNaN, kNaN)); },
               {"circulant", "non-finite"});
  Eigen::Matrix2d m;
  m << 1, 0, 0, kNaN;
  expect_error([&] { Stiffness::dense(m); }, {"dense M", "non-finite", "(1, 1)"});
}

TEST(BadInput, MNotSymmetricSaysHowFar) {
  Eigen::Matrix2d m;
  m << 2, 1, 1.001, 2;
  expect_error([&] { Stiffness::dense(m); },
               {"not symmetric", "|M(1,0) - M(0,1)| = 0.001", "relative"});
  expect_error([] { Stiffness::circulant(Eigen::Vector4d(2, -1, 0, -0.5)); },
               {"circulant M is not symmetric", "entries 1 and 3 differ by -0.5"});
}

TEST(BadInput, MNotPositiveSemiDefiniteSaysHowFar) {
  Eigen::Matrix2d m;
  m << 1, 2, 2, 1;  // eigenvalues -1, 3
  expect_error([&] { Stiffness::dense(m); },
               {"not positive semi-definite", "is -1", "relative -0.333"});
  expect_error([] { Stiffness::diagonal(Eigen::Vector2d(1, -0.5)); },
               {"not positive semi-definite", "-0.5"});
  expect_error([] { Stiffness::circulant(Eigen::Vector4d(1, -1, 0, -1)); },
               {"not positive semi-definite", "is -1"});
  expect_error([] { Stiffness::scalar(-1); }, {"not positive semi-definite"});
}

TEST(BadInput, UnknownMethodListsTheKnownOnes) {
  expect_error([] { Method::by_name("SERKN9s9"); },
               {"unknown method 'SERKN9s9'", "SERKN3s4(1)", "RKN1s2(1)"});
}

TEST(BadInput, StepSizeNearAPoleNamesThePoleAndTheNearestSafeStep) {
  for (const Method& m : methods_of(Kind::erkn)) {
    if (m.poles().empty()) continue;
    SCOPED_TRACE(std::string(m.name()));
    const double P = m.poles()[0], lambda = 4.0;
    const double h = std::sqrt(P * (1 + 3e-7) / lambda);
    System s = polynomial_system();
    s.M = Stiffness::diagonal(Eigen::Vector3d(1.0, lambda, 0.5));
    std::string message;
    try {
      Integrator(m, s, h, kQ, kP);
    } catch (const Error& e) {
      message = e.what();
    }
    EXPECT_NE(message.find("of the pole v = "), std::string::npos) << message;
    EXPECT_NE(message.find("eigenvalue 1 of M"), std::string::npos) << message;
    const auto at = message.find("nearest safe step size h = ");
    ASSERT_NE(at, std::string::npos) << message;
    const double safe = std::stod(message.substr(at + 27));
    EXPECT_NEAR(safe, h, 1e-6 * h);
    EXPECT_NO_THROW(Integrator(m, s, safe, kQ, kP));
    // On a running integrator the refused h changes nothing.
    Integrator run(m, s, 0.01, kQ, kP);
    run.step();
    const Eigen::VectorXd q = run.q();
    EXPECT_THROW(run.set_step_size(h), Error);
    EXPECT_EQ(run.h(), 0.01);
    EXPECT_EQ(run.q(), q);
  }
}

TEST(BadInput, GradientReturningNonFiniteValues) {
  System s = polynomial_system();
  bool poison = false;
  const auto good = s.gradient;
  s.gradient = [&](const Eigen::VectorXd& q, Eigen::VectorXd& g) {
    good(q, g);
    if (poison) g[1] = kNaN;
  };
  Integrator run(method(), s, 0.1, kQ, kP);
  run.step();
  const Eigen::VectorXd q = run.q(), p = run.p();
  poison = true;
  expect_error([&] { run.step(); },
               {"non-finite value at step 2", "t = 0.1", "stage 1", "unchanged"});
  EXPECT_EQ(run.q(), q);
  EXPECT_EQ(run.p(), p);
  EXPECT_EQ(run.t(), 0.1);
  poison = false;
  run.step();
  EXPECT_EQ(run.statistics().steps, 2);
}

TEST(BadInput, MissingCallbacks) {
  System s = polynomial_system();
  s.potential = nullptr;
  Integrator run(method(), s, 0.1, kQ, kP);
  expect_error([&] { run.energy(); }, {"energy() needs System::potential"});
  s.gradient = nullptr;
  expect_error([&] { Integrator(method(), s, 0.1, kQ, kP); }, {"System::gradient is not set"});
}

TEST(BadInput, EndTimeBeforeTOrNotFinite) {
  Fixture f;
  expect_error([&] { f.run.integrate(0.0); }, {"lies before t"});
  expect_error([&] { f.run.integrate(kNaN); }, {"not finite"});
  expect_error([&] { f.run.integrate(kInf); }, {"not finite"});
  f.expect_unchanged();
}

}  // namespace
}  // namespace erkn::test
