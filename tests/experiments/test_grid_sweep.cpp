// predicted_bracket and bracket: the step counts the order predicts bracket the tolerance in few
// runs (from a start far too coarse, from one unstable, and from one far too fine), and stop at the
// step cap when the tolerance is out of reach.
#include <gtest/gtest.h>

#include "grid_sweep.hpp"
#include "interpolate.hpp"
#include "splitting.hpp"
#include "summary.hpp"
#include "sweep.hpp"

namespace ex {
namespace {

// Duffing at t = 1 against its exact solution (omega = 10: Verlet is unstable at 4 steps).
Problem duffing_at_one() {
  Problem p = duffing();
  p.t_error = 1;
  return p;
}

// Some run within tolerance has a successful run beyond it right below it in step count.
bool bracketed(const std::vector<Measurement>& ms, double tolerance) {
  for (size_t i = 0; i + 1 < ms.size(); ++i)
    if (ms[i].ok() && ms[i].error > tolerance && ms[i + 1].ok() && ms[i + 1].error <= tolerance)
      return true;
  return false;
}

TEST(GridSweep, OrderPredictionBracketsTheToleranceInFewRuns) {
  const Problem pr = duffing_at_one();
  const Vec q_ref = (*pr.exact)(pr.t_error);
  SweepPolicy policy;
  policy.timing.repeats = 1;
  policy.max_steps = 1 << 18;
  std::vector<std::unique_ptr<Solver>> solvers;
  solvers.push_back(make_stormer_verlet());
  solvers.push_back(make_splitting(blanes_moan_srkn6b()));
  for (const auto& s : solvers)
    for (long start : {4L, 100000L}) {
      SCOPED_TRACE(s->name() + ", start " + std::to_string(start));
      const auto ms = predicted_bracket(*s, pr, q_ref, 1e-8, start, policy);
      std::string runs;
      for (const Measurement& m : ms)
        runs += " " + std::to_string(m.steps) + ":" + std::to_string(std::log10(m.error));
      SCOPED_TRACE("runs (steps:log10 error)" + runs);
      EXPECT_TRUE(bracketed(ms, 1e-8));
      EXPECT_LE(ms.size(), 5u);
      EXPECT_TRUE(cost_to_tolerance(ms, 1e-8).cpu.has_value());
      EXPECT_TRUE(std::is_sorted(ms.begin(), ms.end(),
                                 [](const auto& a, const auto& b) { return a.steps < b.steps; }));
      // The prediction from the run nearest the tolerance lies between the bracketing counts.
      const double n = predicted_steps(ms, 1e-8, s->order());
      EXPECT_GT(n, 0.5 * double(ms.front().steps));
      EXPECT_LT(n, 2.0 * double(ms.back().steps));
    }
  // Verlet from 4 steps: the first run is unstable (h omega = 2.5 > 2), the sweep recovers.
  const auto verlet = predicted_bracket(*solvers[0], pr, q_ref, 1e-8, 4, policy);
  EXPECT_FALSE(verlet.front().ok());
}

// bracket (the scaling scene's sweep) with several tolerances crosses each of them, from a start
// within the finest (it halves) and one above the coarsest (it doubles). Negative control: a
// bracket of the finest alone from the fine start never reaches the coarse one.
TEST(GridSweep, BracketCrossesEveryTolerance) {
  const Problem pr = duffing_at_one();
  const Vec q_ref = (*pr.exact)(pr.t_error);
  SweepPolicy policy;
  policy.timing.repeats = 1;
  const auto srkn6b = make_splitting(blanes_moan_srkn6b());
  const std::vector<double> tols{1e-6, 1e-10};
  for (long start : {4096L, 8L}) {
    SCOPED_TRACE("start " + std::to_string(start));
    const auto ms = bracket(*srkn6b, pr, pr.t_error, q_ref, tols, start, policy);
    for (double tol : tols) EXPECT_TRUE(bracketed(ms, tol)) << tol;
  }
  EXPECT_FALSE(bracketed(bracket(*srkn6b, pr, pr.t_error, q_ref, {1e-10}, 4096, policy), 1e-6));
}

TEST(GridSweep, StopsAtTheStepCapWhenTheToleranceIsOutOfReach) {
  const Problem pr = duffing_at_one();
  const Vec q_ref = (*pr.exact)(pr.t_error);
  SweepPolicy policy;
  policy.timing.repeats = 1;
  policy.max_steps = 64;
  const auto verlet = make_stormer_verlet();
  const auto ms = predicted_bracket(*verlet, pr, q_ref, 1e-10, 16, policy);
  EXPECT_FALSE(bracketed(ms, 1e-10));
  EXPECT_FALSE(cost_to_tolerance(ms, 1e-10).cpu.has_value());
  EXPECT_EQ(ms.back().steps, 64);
  EXPECT_GT(predicted_steps(ms, 1e-10, verlet->order()), 64);
}

}  // namespace
}  // namespace ex
