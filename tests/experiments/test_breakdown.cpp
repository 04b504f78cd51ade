// The breakdown of a CPU ratio into steps × ∇U per step × CPU per ∇U, the ratios at overhead
// parity and the intrinsic one, and the verdict built on them, on synthetic power-law runs whose
// answers are known in closed form.
#include <gtest/gtest.h>

#include <cmath>

#include "breakdown.hpp"
#include "targets.hpp"
#include "verdict.hpp"

namespace ex {
namespace {

// A method whose error is C h^p on [0, 10], with e ∇U per step, s implicit stages (0: explicit)
// and t seconds per ∇U.
struct Law {
  double C;
  int p;
  double e, s, t;
};

std::vector<Measurement> runs(const Law& law) {
  std::vector<Measurement> ms;
  for (long n = 8; n <= 1 << 16; n *= 2) {
    Measurement m;
    m.steps = n;
    m.h = 10.0 / double(n);
    m.error = law.C * std::pow(m.h, law.p);
    m.stats.steps = n;
    m.stats.grad_evals = std::lround(law.e * double(n));
    m.stats.stage_solves = std::lround(law.s * double(n));
    m.cpu = double(m.stats.grad_evals) * law.t;
    ms.push_back(m);
  }
  return ms;
}

// Steps to `tol` of a law, in closed form.
double steps_to(const Law& law, double tol) { return 10 / std::pow(tol / law.C, 1.0 / law.p); }

MethodResult method(const std::string& name, Family family, bool paper, bool explicit_method,
                    const Law& law) {
  MethodResult m{{name, family, paper, explicit_method, family != Family::rkn, law.p}, {}, {}, {}};
  m.sweep = runs(law);
  return m;
}

ProblemResult problem(std::vector<MethodResult> methods) {
  ProblemResult r{"X", "synthetic", 10, {}, {}};
  r.methods = std::move(methods);
  return r;
}

constexpr double kTol = 1e-6;
const Law kPaper{1e-1, 4, 2.6, 2, 2e-6};     // 2 stages, 1.3 ∇U per stage, slow per ∇U
const Law kPaper2{1e-4, 4, 9.0, 3, 4e-6};    // 3 stages, 3 ∇U per stage, small error constant
const Law kPeer{1e-3, 4, 4.0, 0, 1e-6};      // exact-flow splitting, 4 kicks a step
const Law kExplicit{5e-4, 4, 5.0, 0, 1e-6};  // an explicit registry method

TEST(Breakdown, FactorsMultiplyToTheCpuRatioAndMatchTheLaws) {
  const ProblemResult r = problem({method("paper", Family::erkn, true, false, kPaper),
                                   method("peer", Family::peer, false, true, kPeer)});
  const SceneRuns s = scene_runs(r, kTol);
  const Best peer = best_of(s, Group::peer);
  ASSERT_EQ(peer.name, "peer");
  const auto b = breakdown(s, s.runs[0], peer);
  ASSERT_TRUE(b);
  EXPECT_NEAR(b->cpu, b->steps * b->evals_per_step * b->cpu_per_eval, 1e-9 * b->cpu);
  EXPECT_NEAR(b->steps, steps_to(kPaper, kTol) / steps_to(kPeer, kTol), 1e-3 * b->steps);
  EXPECT_NEAR(b->evals_per_step, kPaper.e / kPeer.e, 1e-3);
  EXPECT_NEAR(b->cpu_per_eval, kPaper.t / kPeer.t, 1e-3);
  EXPECT_NEAR(b->at_parity, b->steps * kPaper.e / kPeer.e, 1e-3 * b->at_parity);
  ASSERT_TRUE(b->evals_per_stage && b->intrinsic);
  EXPECT_NEAR(*b->evals_per_stage, kPaper.e / kPaper.s, 1e-3);
  // At 1.3 ∇U per stage already, the intrinsic ratio is the parity ratio.
  EXPECT_NEAR(*b->intrinsic, b->at_parity, 1e-3 * b->at_parity);
}

TEST(Breakdown, ExplicitMethodsHaveNoIntrinsicStageRatio) {
  const ProblemResult r = problem({method("explicit", Family::erkn, false, true, kExplicit),
                                   method("peer", Family::peer, false, true, kPeer)});
  const SceneRuns s = scene_runs(r, kTol);
  const auto b = breakdown(s, s.runs[0], best_of(s, Group::peer));
  ASSERT_TRUE(b);
  EXPECT_FALSE(b->intrinsic);
  EXPECT_FALSE(b->evals_per_stage);
  EXPECT_FALSE(smallest_intrinsic(s, Group::shipped_explicit, best_of(s, Group::peer)));
}

TEST(Breakdown, NoBreakdownWhenTheToleranceIsOutOfReach) {
  const ProblemResult r = problem({method("paper", Family::erkn, true, false, kPaper),
                                   method("peer", Family::peer, false, true, kPeer)});
  const SceneRuns s = scene_runs(r, 1e-30);
  EXPECT_FALSE(best_of(s, Group::peer).cpu);
  EXPECT_FALSE(breakdown(s, s.runs[0], best_of(s, Group::peer)));
}

TEST(Breakdown, SmallestIntrinsicNeedNotBeTheFastest) {
  // paper2 is slower in CPU (3 ∇U per stage, 2× the CPU per ∇U) but its error constant is 1000×
  // smaller: at 1.3 ∇U per stage it would need fewer evaluations.
  const ProblemResult r = problem({method("paper", Family::erkn, true, false, kPaper),
                                   method("paper2", Family::erkn, true, false, kPaper2),
                                   method("peer", Family::peer, false, true, kPeer)});
  const SceneRuns s = scene_runs(r, kTol);
  const Best peer = best_of(s, Group::peer);
  EXPECT_EQ(best_of(s, Group::paper).name, "paper");
  const auto in = smallest_intrinsic(s, Group::paper, peer);
  ASSERT_TRUE(in);
  EXPECT_EQ(in->method, "paper2");
  const double expected =
      steps_to(kPaper2, kTol) / steps_to(kPeer, kTol) * kEvalsPerStage * kPaper2.s / kPeer.e;
  EXPECT_NEAR(*in->intrinsic, expected, 1e-3 * expected);
}

TEST(Verdict, ListsTheScenesAboveTheTargetWithTheirIntrinsicRatio) {
  const ProblemResult slow = problem({method("paper", Family::erkn, true, false, kPaper),
                                      method("peer", Family::peer, false, true, kPeer)});
  const std::string above = verdict_markdown({scene_runs(slow, kTol)}, {});
  EXPECT_NE(above.find("not in 1 of 1"), std::string::npos) << above;
  EXPECT_NE(above.find("intrinsic"), std::string::npos) << above;
  // Negative control: a paper method as fast as the peer is within the target everywhere.
  Law fast = kPeer;
  fast.s = 2;
  const ProblemResult ok = problem({method("paper", Family::erkn, true, false, fast),
                                    method("peer", Family::peer, false, true, kPeer)});
  const std::string within = verdict_markdown({scene_runs(ok, kTol)}, {});
  EXPECT_NE(within.find("everywhere"), std::string::npos) << within;
  EXPECT_EQ(within.find("not in"), std::string::npos) << within;
}

}  // namespace
}  // namespace ex
