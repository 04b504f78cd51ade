// Output at any time: integrate to an off-grid t_end (a last shorter step with its own
// coefficients), state_at / output times between grid points, observers every k steps, and the
// step-count and grid-resolution limits (issue 12, defects 1 and 2).
#include <gtest/gtest.h>

#include <cstdio>
#include <map>

#include "problems.hpp"
#include "refusals.hpp"

namespace erkn::test {
namespace {

const Eigen::Vector3d kQ(0.6, -0.4, 0.3), kP(0.2, 0.5, -0.7);

Integrator make(double h, const Method& m = Method::by_name("SERKN2s4")) {
  return Integrator(m, polynomial_system(), h, kQ, kP);
}

TEST(Output, OffGridEndTakesWholeStepsThenOneShorterStepOfTheSameMethod) {
  Integrator a = make(0.1), b = make(0.1);
  a.integrate(0.35);
  EXPECT_EQ(a.t(), 0.35);
  EXPECT_EQ(a.statistics().steps, 4);
  for (int k = 0; k < 3; ++k) b.step();
  Integrator c(b.method(), polynomial_system(), 0.35 - b.t(), b.q(), b.p());
  c.step();  // the shorter step, by a fresh integrator whose h is that step
  EXPECT_LT((a.q() - c.q()).norm(), 1e-15);
  EXPECT_LT((a.p() - c.p()).norm(), 1e-15);
  a.step();  // the grid restarts at 0.35
  EXPECT_DOUBLE_EQ(a.t(), 0.45);
}

TEST(Output, EndTimeWithinRoundOffOfTheGridIsTheGridPoint) {
  Integrator a = make(0.1);
  a.integrate(0.3);  // 3 * 0.1 = 0.30000000000000004
  EXPECT_EQ(a.statistics().steps, 3);
  EXPECT_EQ(a.steps_until(0.3), 0);
}

TEST(Output, ObserverEveryKStepsAndAtTheEnd) {
  for (const double t_end : {1.0, 1.05}) {
    Integrator a = make(0.1);
    std::vector<double> times;
    a.integrate(
        t_end,
        [&](double t, const Eigen::VectorXd&, const Eigen::VectorXd&) { times.push_back(t); }, 3);
    ASSERT_EQ(times.size(), 4u) << t_end;
    EXPECT_NEAR(times[0], 0.3, 1e-15);
    EXPECT_NEAR(times[2], 0.9, 1e-15);
    EXPECT_EQ(times[3], t_end);
  }
  Integrator a = make(0.1);
  EXPECT_NE(error_of([&] {
              a.integrate(
                  1.0, [](double, auto&, auto&) {}, 0);
            }).find("observer interval must be >= 1"),
            std::string::npos);
  EXPECT_EQ(a.t(), 0.0);
}

// Issue 12, defect 1: the step count 1e31 used to overflow a long (undefined behaviour) and
// integrate returned at once without a step or an error.
TEST(Output, StepCountBeyondTheLimitIsAClearError) {
  Integrator a = make(0.1);
  const std::string what = error_of([&] { a.integrate(1e30); });
  EXPECT_NE(what.find("step-count limit 2^53"), std::string::npos) << what;
  EXPECT_NE(error_of([&] { a.steps_until(1e30); }), "");
  EXPECT_EQ(a.t(), 0.0);
  EXPECT_EQ(a.statistics().steps, 0);
  EXPECT_EQ(a.steps_until(1e13), 100000000000000L);  // 1e14 steps: within the limit
}

// Issue 12, defect 2: the whole-number tolerance used to scale with |t_end|, so t_end = 1e8 +
// 0.05 (h = 0.1) ended at 1e8 + 0.1, and 1e7 + 0.01 (h = 0.02) at 1e7 + 0.02.
TEST(Output, LargeOffGridEndTimesEndExactlyThere) {
  for (const auto& [t0, h, rest] : {std::tuple{1e8, 0.1, 0.05}, std::tuple{1e7, 0.02, 0.01}}) {
    Integrator a = make(h);
    a.set_state(kQ, kP, t0);
    a.integrate(t0 + rest);
    EXPECT_EQ(a.t(), t0 + rest);
    EXPECT_EQ(a.statistics().steps, 1);
    // One step of the representable t0 + rest - t0 from the same state.
    Integrator b(a.method(), polynomial_system(), (t0 + rest) - t0, kQ, kP);
    b.step();
    EXPECT_LT((a.q() - b.q()).norm(), 1e-15);
  }
  Integrator a = make(0.1);  // on the grid at large t: whole steps only
  a.set_state(kQ, kP, 1e8);
  a.integrate(1e8 + 0.3);
  EXPECT_EQ(a.statistics().steps, 3);
}

TEST(Output, StepSizeBelowTheRoundOffOfTIsRefused) {
  Integrator a = make(1e-9);
  a.set_state(kQ, kP, 1e8);
  EXPECT_NE(error_of([&] { a.integrate(1e8 + 1); }).find("time grid cannot be resolved"),
            std::string::npos);
}

TEST(Output, OutputTimesDoNotChangeTheTrajectory) {
  Integrator a = make(0.1), b = make(0.1);
  Eigen::VectorXd times(4);
  times << 0.0, 0.123, 0.5, 0.77;
  std::vector<double> seen;
  a.integrate(0.8, times, [&](double t, const Eigen::VectorXd& q, const Eigen::VectorXd&) {
    seen.push_back(t);
    if (t == 0.0) EXPECT_EQ(q, Eigen::VectorXd(kQ));
  });
  b.integrate(0.8);
  EXPECT_EQ(seen, std::vector<double>(times.begin(), times.end()));
  EXPECT_EQ(a.q(), b.q());
  EXPECT_EQ(a.p(), b.p());
  EXPECT_EQ(a.statistics().steps, b.statistics().steps);
  EXPECT_GT(a.statistics().gradient_evaluations, b.statistics().gradient_evaluations);
  Eigen::VectorXd bad(2);
  bad << 0.5, 0.4;
  EXPECT_NE(
      error_of([&] { a.integrate(2.0, bad, [](double, auto&, auto&) {}); }).find("not ascending"),
      std::string::npos);
  Eigen::VectorXd q, p;
  EXPECT_NE(error_of([&] { a.state_at(a.t() + 0.2, q, p); }).find("within one step"),
            std::string::npos);
}

// Output between grid points has the method's order: the global error at the grid point before
// plus the local error of the shorter step. The fit as in order_test.cpp (observed_order against
// a long-double reference, stage equations solved to round-off) of the largest error at 40 output
// times: their positions theta in a step vary with h, and so do the h^(p+1) terms of the shorter
// step; at 3 output times they still scattered SRKN14a's slope to 5.4..6.2. Negative control:
// the state at the grid point before (zero-order hold, error ~ |p| theta h) fails the same fit.
// A processed method runs over 10 T (order_test.cpp: pi's error at the ends does not grow, and
// over T it is still comparable with the accumulated part), with h = T / n as the others.
TEST(Output, OutputBetweenGridPointsHasTheOrderOfTheMethod) {
  const double T = 2.0;
  std::vector<double> at, at_long;  // off the grid for every h below
  for (int j = 0; j < 40; ++j)
    at.push_back(T * (j + 0.5) / 40 + 0.0123), at_long.push_back(10 * T * (j + 0.5) / 40 + 0.0123);
  const Eigen::VectorXd times = Eigen::Map<Eigen::VectorXd>(at.data(), Eigen::Index(at.size()));
  const Eigen::VectorXd times_long =
      Eigen::Map<Eigen::VectorXd>(at_long.data(), Eigen::Index(at_long.size()));
  const Reference ref = polynomial_reference(kQ, kP, at);
  const Reference ref_long = polynomial_reference(kQ, kP, at_long);
  EXPECT_LT(ref.accuracy, 1e-15);
  EXPECT_LT(ref_long.accuracy, 1e-15);
  Options solved_to_round_off;
  solved_to_round_off.tolerance = 0;
  for (const Method& m : Method::all()) {
    SCOPED_TRACE(std::string(m.name()));
    const bool long_run = m.is_processed();
    std::map<long, double> hold;  // error of the zero-order hold, by step count
    auto error_at = [&](long n) {
      Integrator run(m, polynomial_system(), T / double(n), kQ, kP, solved_to_round_off);
      double err = 0, err_hold = 0;
      size_t k = 0;
      const Reference& r = long_run ? ref_long : ref;
      run.integrate(long_run ? 10 * T : T, long_run ? times_long : times,
                    [&](double, const Eigen::VectorXd& q, const Eigen::VectorXd&) {
                      err = std::max(err, (q - r.q[k]).norm());
                      err_hold =
                          std::max(err_hold, (run.q() - r.q[k]).norm());  // (the grid point before)
                      ++k;
                    });
      hold[n] = err_hold;
      return err;
    };
    const ObservedOrder o = observed_order(error_at);
    ASSERT_GE(o.n.size(), 3u);
    std::vector<double> y_hold;
    for (long n : o.n) y_hold.push_back(hold.at(n));
    std::printf(
        "%-14s order %d: output between grid points, observed order %.3f (h = T/%ld..T/%ld)\n",
        std::string(m.name()).c_str(), m.order(), o.slope, o.n.front(), o.n.back());
    EXPECT_NEAR(o.slope, m.order(), 0.15);
    EXPECT_LT(fitted_slope(o.n, y_hold), m.order() - 0.5);
  }
}

// Over a long run the energy of the output between grid points stays within the grid's own
// energy error (no drift), and so does stepping to each output time with a shorter step.
TEST(Output, EnergyAtOutputTimesBehavesLikeTheGrid) {
  const double h = 0.1, T = 1000;
  for (const Method& m : methods_of(Kind::erkn)) {
    SCOPED_TRACE(std::string(m.name()));
    Integrator grid = make(h, m), stepped = make(h, m);
    const double H0 = grid.energy();
    double e_grid = 0, e_out[2] = {0, 0}, e_step[2] = {0, 0};
    grid.integrate(
        T, [&](double, auto&, auto&) { e_grid = std::max(e_grid, std::abs(grid.energy() - H0)); });
    Integrator out = make(h, m);
    Eigen::VectorXd times = Eigen::VectorXd::LinSpaced(2000, 0.0, T).array() + 0.0371;
    times[times.size() - 1] = T;
    out.integrate(T, times, [&](double t, const Eigen::VectorXd& q, const Eigen::VectorXd& p) {
      e_out[t > T / 2] = std::max(e_out[t > T / 2], std::abs(out.energy(q, p) - H0));
      stepped.integrate(t);
      e_step[t > T / 2] = std::max(e_step[t > T / 2], std::abs(stepped.energy() - H0));
    });
    std::printf(
        "%-14s max |H - H0| over t <= %g: grid %.2e; output between grid points %.2e "
        "(first half) %.2e (second half); stepping to each output time %.2e %.2e\n",
        std::string(m.name()).c_str(), T, e_grid, e_out[0], e_out[1], e_step[0], e_step[1]);
    EXPECT_LE(std::max(e_out[0], e_out[1]), 1.5 * e_grid);
    EXPECT_LE(e_out[1], 2 * e_out[0]);
    EXPECT_LE(e_step[1], 2 * e_step[0]);
  }
}

}  // namespace
}  // namespace erkn::test
