// The interleaved re-timing and the measured noise of a ratio: which runs are timed again, the
// range of a ratio over the rounds, and the recognition of two codes of the same method.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "problem.hpp"
#include "retime.hpp"
#include "splitting.hpp"

namespace ex {
namespace {

// A solver that runs another `times` times per run: the same results at `times` the cost.
class Slowed : public Solver {
 public:
  Slowed(std::unique_ptr<Solver> inner, int times) : inner_(std::move(inner)), times_(times) {}
  std::string name() const override { return "slowed " + inner_->name(); }
  Family family() const override { return inner_->family(); }
  int order() const override { return inner_->order(); }
  bool exact_for_linear_part() const override { return inner_->exact_for_linear_part(); }
  bool is_explicit() const override { return inner_->is_explicit(); }
  RunResult run(const Problem& p, double h, long steps, const Observer* obs) const override {
    for (int k = 1; k < times_; ++k) inner_->run(p, h, steps, obs);
    return inner_->run(p, h, steps, obs);
  }

 private:
  std::unique_ptr<Solver> inner_;
  int times_;
};

// Runs with error C h^p at step counts 8, 16, ..., 1024 on [0, 10], CPU time t per step.
std::vector<Measurement> law(double C, int p, double t) {
  std::vector<Measurement> ms;
  for (long n = 8; n <= 1024; n *= 2) {
    Measurement m;
    m.steps = m.stats.steps = n;
    m.h = 10.0 / double(n);
    m.error = C * std::pow(m.h, p);
    m.cpu = t * double(n);
    ms.push_back(m);
  }
  return ms;
}

TEST(SameMethod, EqualErrorsAtEqualStepsAndNothingElse) {
  const auto a = law(1e-3, 4, 1e-6);
  EXPECT_TRUE(same_method(a, law(1e-3, 4, 3e-6)));  // CPU time does not matter
  // Negative controls: another error constant, another order, no common step counts.
  EXPECT_FALSE(same_method(a, law(1.001e-3, 4, 1e-6)));
  EXPECT_FALSE(same_method(a, law(1e-3, 5, 1e-6)));
  auto shifted = law(1e-3, 4, 1e-6);
  for (Measurement& m : shifted) m.steps += 1;
  EXPECT_FALSE(same_method(a, shifted));
  // Errors at round-off say nothing: two methods agreeing only there are not the same.
  auto tiny = law(1e-3, 4, 1e-6), other = law(1e-3, 4, 1e-6);
  for (size_t i = 0; i < tiny.size(); ++i) tiny[i].error = 1e-12, other[i].error = 3e-12;
  EXPECT_FALSE(same_method(tiny, other));
}

TEST(SameMethod, RecognisesTwoRunsOfOneSplittingAndNotAnother) {
  const Problem p = stellar_orbits();
  const Vec ref = reference_solution(p, p.t_error, 1e-15).q;
  const TimingPolicy once{1, 0, 0};
  auto sweep_of = [&](const Solver& s) {
    std::vector<Measurement> ms;
    for (long n : {100, 200, 400}) ms.push_back(measure(s, p, p.t_error, n, ref, once));
    return ms;
  };
  const auto strang = sweep_of(*make_splitting(ex::strang()));
  EXPECT_TRUE(same_method(strang, sweep_of(Slowed(make_splitting(ex::strang()), 2))));
  EXPECT_FALSE(same_method(strang, sweep_of(*make_splitting(blanes_moan_srkn6b()))));
}

TEST(BestRatio, RangeOverTheRoundsAndItsTarget) {
  std::vector<MethodResult> methods(2);
  methods[0].name = "method", methods[0].family = Family::erkn;
  methods[1].name = "peer", methods[1].family = Family::peer;
  methods[0].sweep = law(1e-3, 4, 2e-6), methods[1].sweep = law(1e-3, 4, 1e-6);
  ProblemResult r{"X", "synthetic", 10, {}, std::move(methods)};
  const SceneRuns s = scene_runs(r, 1e-6);
  const auto plain = best_ratio(s, Group::shipped, Group::peer);
  ASSERT_TRUE(plain);
  EXPECT_NEAR(plain->value, 2, 1e-12);
  EXPECT_FALSE(plain->low || plain->high);  // no rounds: no range, never "within noise"
  EXPECT_FALSE(plain->straddles(2));
  // Three rounds: the method at 1, 1.2 and 1.35 times its best, the peer at its best.
  for (Measurement& m : r.methods[0].sweep) m.round_cpu = {m.cpu * 1.2, m.cpu, m.cpu * 1.35};
  for (Measurement& m : r.methods[1].sweep) m.round_cpu = {m.cpu, m.cpu, m.cpu};
  EXPECT_EQ(timing_rounds(s), 3);
  const auto ranged = best_ratio(s, Group::shipped, Group::peer);
  ASSERT_TRUE(ranged && ranged->low && ranged->high);
  EXPECT_NEAR(*ranged->low, 2, 1e-9);
  EXPECT_NEAR(*ranged->high, 2.7, 1e-9);
  EXPECT_TRUE(ranged->straddles(2.5));
  EXPECT_FALSE(ranged->straddles(3));
  EXPECT_FALSE(ranged->straddles(1));
}

TEST(Retime, ContendersAreTimedInEveryRoundAndTheSlowAreNot) {
  const Problem p = stellar_orbits();
  const Vec ref = reference_solution(p, p.t_error, 1e-15).q;
  TimingPolicy timing{5, 0.5, 0.01};  // first-pass times of 10 ms at least: 4× apart
  timing.rounds = 3;
  timing.round_sample = 1e-3;
  SolverList solvers;
  solvers.push_back(make_splitting(blanes_moan_srkn6b()));
  solvers.push_back(std::make_unique<Slowed>(make_splitting(blanes_moan_srkn6b()), 4));
  std::vector<MethodResult> methods;
  for (const auto& s : solvers) {
    MethodResult m{traits_of(*s), {}, {}, {}};
    for (long n : {25, 50, 100, 200, 400, 800})
      m.sweep.push_back(measure(*s, p, p.t_error, n, ref, timing));
    methods.push_back(std::move(m));
  }
  // A tolerance between the 3rd and 4th runs: those two decide the cost.
  const double tol = std::sqrt(methods[0].sweep[2].error * methods[0].sweep[3].error);
  std::vector<TimedLine> lines;
  for (size_t i = 0; i < solvers.size(); ++i)
    lines.push_back({solvers[i].get(), &methods[i], &methods[i].sweep});
  retime_contenders(p, lines, {tol}, timing);

  const auto& fast = methods[0].sweep;
  for (size_t i = 0; i < fast.size(); ++i) {
    if (i == 2 || i == 3) {
      ASSERT_EQ(fast[i].round_cpu.size(), 3u) << i;
      EXPECT_EQ(fast[i].cpu, *std::min_element(fast[i].round_cpu.begin(), fast[i].round_cpu.end()));
    } else {
      EXPECT_TRUE(fast[i].round_cpu.empty()) << i;  // too slow to decide, or outside the bracket
    }
  }
  for (const Measurement& m : methods[1].sweep) EXPECT_TRUE(m.round_cpu.empty());
}

}  // namespace
}  // namespace ex
