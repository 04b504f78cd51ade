// Events (erkn/events.hpp): zeros of g(t, q, p) located on the method's own shorter step, with
// SciPy's direction and terminal; the run is the same with or without events.
#include "erkn/events.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "problems.hpp"

namespace erkn::test {
namespace {

using Vec = Eigen::VectorXd;
constexpr double kPi = std::numbers::pi;

// q'' + 4 q = 0 from q = 1, p = 0: q = cos 2t, exactly what every ERKN method computes (U = 0),
// so the zeros of q, t = pi/4 + k pi/2, are located to round-off.
Integrator oscillator(const Method& m, double h) {
  System s;
  s.M = Stiffness::scalar(4);
  s.gradient = [](const Vec&, Vec& g) { g.setZero(); };
  s.hessian_vector_product = [](const Vec&, const Vec& v, Vec& hv) { hv.setZero(v.size()); };
  return Integrator(m, s, h, Vec::Constant(1, 1.0), Vec::Zero(1));
}

Event q_zero(int direction, bool terminal = false) {
  return {[](double, const Vec& q, const Vec&) { return q[0]; }, direction, terminal};
}

TEST(Events, ZerosOfAnExactFlowAreLocatedToRoundOffForEveryErknMethod) {
  for (const Method& m : methods_of(Kind::erkn)) {
    Integrator run = oscillator(m, 0.3);
    Events events(run, {q_zero(-1), q_zero(+1)});
    events.integrate(run, 10.0, [](double, const Vec&, const Vec&) {});
    ASSERT_EQ(events.hits().size(), 6u) << m.name();  // zeros at pi/4 + k pi/2 < 10
    for (std::size_t k = 0; k < 6; ++k) {
      const EventHit& e = events.hits()[k];
      EXPECT_NEAR(e.t, kPi / 4 + double(k) * kPi / 2, 1e-13) << m.name();
      EXPECT_EQ(e.event, k % 2 == 0 ? 0u : 1u) << m.name();  // falls first, then rises
      EXPECT_NEAR(e.q[0], 0, 1e-13) << m.name();
    }
  }
}

TEST(Events, TheRunAndItsOutputAreThoseWithoutEvents) {
  const Method m = methods_of(Kind::erkn).front();
  std::vector<double> plain_t, event_t;
  Integrator b(m, polynomial_system(), 0.07, Vec::Constant(3, 0.4), Vec::Constant(3, 0.3));
  Integrator c(m, polynomial_system(), 0.07, Vec::Constant(3, 0.4), Vec::Constant(3, 0.3));
  b.integrate(
      5.01, [&](double t, const Vec&, const Vec&) { plain_t.push_back(t); }, 4);
  Events events(c, {{[](double, const Vec& q, const Vec&) { return q[0] - 0.1; }}});
  events.integrate(
      c, 5.01, [&](double t, const Vec&, const Vec&) { event_t.push_back(t); }, 4);
  EXPECT_EQ(plain_t, event_t);
  EXPECT_EQ(b.q(), c.q());
  EXPECT_EQ(b.p(), c.p());
  EXPECT_FALSE(events.hits().empty());
  EXPECT_GT(events.statistics().gradient_evaluations, 0);
}

TEST(Events, ATerminalEventLeavesTheRunAtItsTimeAndState) {
  const Method m = methods_of(Kind::erkn).front();
  Integrator run = oscillator(m, 0.3);
  Events events(run, {q_zero(+1, true), q_zero(-1)});
  double last = -1;
  EXPECT_TRUE(events.integrate(run, 10.0, [&](double t, const Vec&, const Vec&) { last = t; }));
  ASSERT_EQ(events.hits().size(), 2u);  // the fall at pi/4, then the terminal rise at 3 pi/4
  EXPECT_NEAR(run.t(), 3 * kPi / 4, 1e-13);
  EXPECT_EQ(last, run.t());
  EXPECT_EQ(run.q(), events.hits().back().q);
  // negative control: not terminal, the run reaches t_end
  Integrator on = oscillator(m, 0.3);
  Events passing(on, {q_zero(+1)});
  EXPECT_FALSE(passing.integrate(on, 10.0, [](double, const Vec&, const Vec&) {}));
  EXPECT_EQ(on.t(), 10.0);
}

TEST(Events, BadEventsAreRefusedNamingTheEvent) {
  Integrator run = oscillator(methods_of(Kind::erkn).front(), 0.3);
  EXPECT_THROW(
      {
        try {
          Events(run, {q_zero(0), q_zero(2)});
        } catch (const Error& e) {
          EXPECT_NE(std::string(e.what()).find("event 1: direction"), std::string::npos);
          throw;
        }
      },
      Error);
  EXPECT_THROW(Events(run, {Event{}}), Error);
  EXPECT_EQ(run.t(), 0.0);
}

}  // namespace
}  // namespace erkn::test
