// The time grid t0 + n h (erkn/time_grid.hpp), the one definition Integrator, the MPI
// GridIntegrator and Python use: times within its round-off window are grid points, times off it
// take whole steps to the last grid point before them and one shorter step, and every refusal
// leaves the grid as it was. Random t0 and h over many magnitudes (fixed seed).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <erkn/erkn.hpp>
#include <erkn/problems.hpp>
#include <erkn/time_grid.hpp>
#include <limits>
#include <random>

#include "refusals.hpp"

namespace erkn::test {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

// (t0, h) pairs: t0 from -1e6 to 1e6 (and 0), h from 1e-4 to 1.
std::vector<TimeGrid> grids() {
  std::mt19937 random(19);
  std::uniform_real_distribution<double> exponent(-4, 6), h_exponent(-4, 0), sign(-1, 1);
  std::vector<TimeGrid> out{TimeGrid(0, 0.1)};
  for (int k = 0; k < 200; ++k)
    out.emplace_back(sign(random) * std::pow(10.0, exponent(random)),
                     std::pow(10.0, h_exponent(random)));
  return out;
}

TEST(TimeGrid, TimesWithinTheRoundOffWindowAreGridPoints) {
  const TimeGrid tenth(0, 0.1);
  EXPECT_EQ(tenth.plan_to(0.1 + 0.2).whole, 3);  // (0.1 + 0.2 = 0.30000000000000004)
  EXPECT_FALSE(tenth.plan_to(0.1 + 0.2).shorter);
  for (const TimeGrid& g : grids())
    for (long k : {0L, 1L, 7L, 1000L}) {
      const double t_k = g.ahead(k), ulp = std::abs(t_k) * kEps;
      for (double t_end : {t_k, std::nextafter(t_k, t_k + 1), t_k + ulp, t_k - ulp}) {
        const TimeGrid::Plan plan = g.plan_to(t_end);
        EXPECT_EQ(plan.whole, k) << g.t() << " + " << k << " * " << g.h();
        EXPECT_FALSE(plan.shorter) << g.t() << " + " << k << " * " << g.h();
      }
      // Negative control: beyond the window t_end is off the grid.
      const double beyond = t_k + 16 * kEps * std::max({std::abs(g.t()), std::abs(t_k), g.h()});
      EXPECT_TRUE(g.plan_to(beyond).shorter) << g.t() << " + " << k << " * " << g.h();
      EXPECT_EQ(g.plan_to(beyond).whole, k);
    }
}

TEST(TimeGrid, AnOffGridTimeTakesWholeStepsToTheLastGridPointBeforeIt) {
  for (const TimeGrid& g : grids())
    for (long k : {0L, 3L, 250L})
      for (double f : {0.01, 0.5, 0.99}) {
        const double t_end = g.ahead(k) + f * g.h();
        const TimeGrid::Plan plan = g.plan_to(t_end);
        ASSERT_TRUE(plan.shorter) << g.t() << " + " << k << " * " << g.h() << ", f " << f;
        EXPECT_EQ(plan.whole, k);
        EXPECT_LT(g.ahead(plan.whole), t_end);
        EXPECT_GT(g.ahead(plan.whole + 1), t_end);
      }
}

// The plan's definition, whatever n plan_to's search starts from: the last grid point at or
// before t_end + tolerance(t_end) (found here by counting; none when t_end is within it of t()),
// shorter unless t_end is within the tolerance of it; on grids already advanced (t() = ahead of the
// start), and on grids whose h is barely above twice the round-off window (the window then reaches
// almost half a step). A search from the rounded quotient that dropped either correction fails here
// (f = 0.5, 0.99: the nearest grid point lies after t_end; f = -0.45 on the coarse grids: t_end
// within the window below a grid point whose quotient rounds below it).
TEST(TimeGrid, ThePlanIsTheLastGridPointWithinTheWindowFromAnyPosition) {
  std::vector<TimeGrid> all = grids();
  for (double t0 : {-1e6, -3.0, -1e-3})  // (|t| decreasing: the window is 4 eps |t0|)
    for (double ratio : {2.01, 2.05, 2.2}) all.emplace_back(t0, ratio * 4 * kEps * std::abs(t0));
  for (TimeGrid g : all) {
    g.advance(37);
    for (long k : {0L, 1L, 7L, 250L})
      for (double f : {-0.45, -1e-17, 0.0, 1e-17, 0.01, 0.5, 0.99}) {
        const double t_end = g.ahead(k) + f * g.h();
        if (t_end < g.t()) continue;
        const double tol = g.tolerance(t_end), last = t_end + tol;
        long n = 0;  // (t_end within the window of t() is t() itself)
        while (t_end - g.t() > tol && g.ahead(n + 1) <= last) ++n;
        const TimeGrid::Plan plan = g.plan_to(t_end);
        EXPECT_EQ(plan.whole, n) << g.t() << " + " << k << " * " << g.h() << ", f " << f;
        EXPECT_EQ(plan.shorter, std::abs(g.ahead(n) - t_end) > tol)
            << g.t() << " + " << k << " * " << g.h() << ", f " << f;
      }
  }
}

TEST(TimeGrid, StepsAdvanceFromTheStartWithoutAccumulatingRoundOff) {
  TimeGrid g(1.0 / 3, 0.1);
  for (int n = 0; n < 100000; ++n) g.advance();
  EXPECT_EQ(g.t(), 1.0 / 3 + 100000 * 0.1);  // t0 + n h, not a running sum
  g.restart(2.5);
  EXPECT_EQ(g.t(), 2.5);
  EXPECT_EQ(g.ahead(2), 2.5 + 2 * 0.1);
}

// Every refusal names the problem and changes nothing.
TEST(TimeGrid, RefusalsNameTheProblemAndLeaveTheGridUnchanged) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (double h : {0.0, -0.1, nan, inf})
    EXPECT_CONTAINS(error_of([&] { TimeGrid(0, h); }), "step size h must be finite and > 0");
  EXPECT_CONTAINS(error_of([&] { TimeGrid(nan, 0.1); }), "is not finite");
  for (TimeGrid g : grids()) {
    const double t = g.t(), h = g.h();
    EXPECT_CONTAINS(error_of([&] { g.plan_to(t - h); }), "lies before t");
    EXPECT_CONTAINS(error_of([&] { g.plan_to(nan); }), "is not finite");
    EXPECT_CONTAINS(error_of([&] { g.plan_to(inf); }), "is not finite");
    EXPECT_CONTAINS(error_of([&] { g.plan_to(t + 1e17 * h); }), "step-count limit 2^53");
    EXPECT_CONTAINS(error_of([&] { g = g.with_step(-h); }), "step size h must be finite");
    EXPECT_CONTAINS(error_of([&] { g = g.with_start(inf); }), "is not finite");
    const Eigen::Vector3d descending(t + 2 * h, t + h, t + 3 * h);
    EXPECT_CONTAINS(error_of([&] { g.require_output_times(t + 3 * h, descending); }),
                    "output time 1");
    const Eigen::Vector2d outside(t + h, t + 5 * h);
    EXPECT_CONTAINS(error_of([&] { g.require_output_times(t + 3 * h, outside); }),
                    "outside [t, t_end]");
    EXPECT_EQ(g.t(), t);
    EXPECT_EQ(g.h(), h);
    const Eigen::Vector3d fine(t, t + 0.5 * h, t + 3 * h);  // negative control: accepted
    EXPECT_NO_THROW(g.require_output_times(t + 3 * h, fine));
  }
  TimeGrid far(1e20, 0.1);
  EXPECT_FALSE(far.resolved());
  EXPECT_CONTAINS(error_of([&] { far.require_resolved(); }), "below the round-off of t");
  EXPECT_TRUE(TimeGrid(1e20, 1e6).resolved());
}

// require_output_times' definition written out: a time is accepted when it is finite and within
// [t, t_end] up to 4 eps max(|t|, |time|, h) and 4 eps max(|t_end|, |time|, h); `edge_sweep` gives
// `count` times one ulp apart around each window's edge, ascending.
struct OutputWindow {
  double t, h, t_end;
  explicit OutputWindow(const TimeGrid& g) : t(g.t()), h(g.h()), t_end(g.t() + 7 * g.h()) {}
  double window(double a, double b) const {
    return 4 * kEps * std::max({std::abs(a), std::abs(b), h});
  }
  bool defined(double tau) const {
    return std::isfinite(tau) && tau >= t - window(t, tau) && tau <= t_end + window(t_end, tau);
  }
  std::vector<double> edge_sweep(int count) const {
    const double inf = std::numeric_limits<double>::infinity();
    std::vector<double> out;
    for (double edge : {t - window(t, t), t_end + window(t_end, t_end)}) {
      double tau = std::nextafter(std::nextafter(edge, -inf), -inf);
      for (int k = 0; k < count; ++k, tau = std::nextafter(tau, inf)) out.push_back(tau);
    }
    return out;
  }
};

// require_output_times accepts exactly the times its definition does (finite, ascending, within
// [t, t_end] up to 4 eps max(|t|, |time|, h) and 4 eps max(|t_end|, |time|, h), the windows
// written out in OutputWindow), at and one ulp beyond each window's edge, and names the first time
// that fails when several do, whatever fails after it.
TEST(TimeGrid, OutputTimesAreCheckedAsDefinedAndTheFirstBadOneIsNamed) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const TimeGrid& g : grids()) {
    const OutputWindow w(g);
    const double t = w.t, h = w.h, t_end = w.t_end;
    int accepted = 0, refused = 0;
    for (double tau : w.edge_sweep(5)) {
      const Eigen::VectorXd one = Eigen::VectorXd::Constant(1, tau);
      const bool ok = error_of([&] { g.require_output_times(t_end, one); }).empty();
      EXPECT_EQ(ok, w.defined(tau)) << "t = " << t << ", h = " << h << ", time " << tau;
      ++(ok ? accepted : refused);
    }
    EXPECT_GT(accepted, 0);  // (both outcomes met at the edges: the sweep crosses them)
    EXPECT_GT(refused, 0);
    for (int j = 0; j < 5; ++j)
      for (double bad : {nan, inf, t - h, t_end + h, t - 1}) {
        Eigen::VectorXd times = Eigen::VectorXd::LinSpaced(5, t, t_end);
        times[j] = bad == t - 1 && j > 0 ? times[j - 1] - h : bad;       // (t - 1: descending)
        for (int k = j + 1; k < 5; ++k) times[k] = k % 2 ? nan : t - h;  // (later ones bad too)
        EXPECT_CONTAINS(error_of([&] { g.require_output_times(t_end, times); }),
                        "output time " + std::to_string(j) + " =");
      }
  }
}

// A list of times is accepted exactly when each of its times would be alone: the ascending lists
// made of the times one ulp apart across both windows' edges (every sub-list, so first, last and
// middle times all meet both edges) are accepted or refused as the definition applied to every
// time says. (require_output_times tests the first and last in full and the rest for order only.)
// Negative control: one time out of order among accepted ones is refused, and named.
TEST(TimeGrid, AListOfTimesIsJudgedAsEachOfItsTimesAlone) {
  for (const TimeGrid& g : grids()) {
    const OutputWindow w(g);
    const double t = w.t, h = w.h, t_end = w.t_end;
    const std::vector<double> sweep = w.edge_sweep(4);
    int accepted = 0, refused = 0;
    for (size_t first = 0; first < sweep.size(); ++first)
      for (size_t last = first; last < sweep.size(); ++last) {
        const Eigen::VectorXd times =
            Eigen::Map<const Eigen::VectorXd>(sweep.data() + first, Eigen::Index(last - first + 1));
        const bool ok = error_of([&] { g.require_output_times(t_end, times); }).empty();
        EXPECT_EQ(
            ok, std::all_of(times.begin(), times.end(), [&](double tau) { return w.defined(tau); }))
            << "t = " << t << ", h = " << h << ", times " << times.transpose();
        ++(ok ? accepted : refused);
      }
    EXPECT_GT(accepted, 0);
    EXPECT_GT(refused, 0);
    Eigen::VectorXd swapped = Eigen::VectorXd::LinSpaced(5, t, t_end);
    std::swap(swapped[2], swapped[3]);
    EXPECT_CONTAINS(error_of([&] { g.require_output_times(t_end, swapped); }), "output time 3 =");
  }
}

// Integrator(..., options, t0) starts on the grid t0 + n h: bit-identical to a start at 0 and
// set_state at t0, for every method.
TEST(TimeGrid, AnIntegratorStartedAtT0IsTheOneMovedThereBySetState) {
  const problems::Problem p = problems::stellar_orbits();
  for (const Method& m : Method::all()) {
    SCOPED_TRACE(std::string(m.name()));
    Integrator started(m, problems::system(p), 0.05, p.q0, p.p0, {}, 2.5);
    Integrator moved(m, problems::system(p), 0.05, p.q0, p.p0);
    moved.set_state(p.q0, p.p0, 2.5);
    EXPECT_EQ(started.t(), 2.5);
    started.integrate(3.33);
    moved.integrate(3.33);
    EXPECT_EQ(started.t(), 3.33);
    EXPECT_EQ(started.q(), moved.q());
    EXPECT_EQ(started.p(), moved.p());
    EXPECT_EQ(started.statistics().steps, moved.statistics().steps);
  }
  EXPECT_CONTAINS(error_of([&] {
                    Integrator(Method::all()[0], problems::system(p), 0.05, p.q0, p.p0, {},
                               std::numeric_limits<double>::infinity());
                  }),
                  "is not finite");
}

}  // namespace
}  // namespace erkn::test
