// The default blow-up guard (Options::blowup_guard): on FPU (omega = 50) at the unstable and
// resonant step sizes h omega = 0.999 pi and 0.999 2 pi, every registry method either stops with
// an erkn::Error (the guard's names the time, the growth and the advisor's verdict; a stage solver
// may refuse first) keeping a state within the energy criterion, or runs 1e5 steps within the
// advisor's "runs clean" bound (relative energy error < 0.5). Never a quiet blow-up. Negative
// control: with the guard off, a run drifts to an energy error ~1e5 without an error.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "problems.hpp"

namespace erkn::test {
namespace {

constexpr double kOmega = kStiffOmega, kPi = std::numbers::pi;
constexpr long kSteps = 100000;

struct Outcome {
  bool stopped = false;
  std::string message;
  double worst = 0;  // max |H - H_0| / |H_0| over the steps taken (sampled every 50 steps)
  double kept = 0;   // |H - H_0| / |H_0| of the state the run ends with
};

Outcome run_fpu(const Method& m, double h, bool guard, bool with_potential = true) {
  System s = problems::system(stiff_fpu());
  const auto U = s.potential;
  if (!with_potential) s.potential = nullptr;
  Options o;
  o.blowup_guard = guard;
  Integrator run(m, s, h, stiff_fpu().q0, stiff_fpu().p0, o);
  const auto H = [&](const Eigen::VectorXd& q, const Eigen::VectorXd& p) {
    Eigen::VectorXd Mq = s.M.to_dense(q.size()) * q;
    return 0.5 * p.squaredNorm() + 0.5 * q.dot(Mq) + U(q);
  };
  const double H0 = H(run.q(), run.p());
  Outcome out;
  const auto observe = [&](double, const Eigen::VectorXd& q, const Eigen::VectorXd& p) {
    const double e = std::abs(H(q, p) - H0) / std::abs(H0);
    out.worst = std::isnan(e) ? INFINITY : std::max(out.worst, e);
  };
  try {
    run.integrate(double(kSteps) * h, observe, 50);
  } catch (const Error& e) {
    out.stopped = true, out.message = e.what();
  }
  out.kept = std::abs(H(run.q(), run.p()) - H0) / std::abs(H0);
  return out;
}

class BlowupGuard : public ::testing::TestWithParam<size_t> {};

TEST_P(BlowupGuard, FpuAtUnstableStepSizesStopsClearlyOrRunsClean) {
  const Method& m = Method::all()[GetParam()];
  for (double h_omega : {0.999 * kPi, 0.999 * 2 * kPi}) {
    SCOPED_TRACE(std::string(m.name()) + " at h omega = " + std::to_string(h_omega / kPi) + " pi");
    const Outcome o = run_fpu(m, h_omega / kOmega, true);
    if (!o.stopped) {
      EXPECT_LT(o.worst, 0.5);
      continue;
    }
    // Any erkn::Error (the guard's, or a stage solver's at the first steps), and the state kept
    // is a good one.
    EXPECT_LE(o.kept, 0.5) << o.message;
    if (o.message.find("blow-up guard: at t = ") != std::string::npos)
      EXPECT_NE(o.message.find("Likely cause:"), std::string::npos) << o.message;
  }
}

INSTANTIATE_TEST_SUITE_P(Registry, BlowupGuard, ::testing::Range(size_t(0), Method::all().size()),
                         [](const auto& info) {
                           std::string n(Method::all()[info.param].id_name());
                           return n;
                         });

// Negative control: the guard is what stops them (SERKN2s4 at 0.999 pi: a relative energy error
// ~1e5 over 1e5 steps without it, docs/stability-advisor.md, "Resonances").
TEST(BlowupGuardControl, WithoutTheGuardTheSameRunBlowsUpQuietly) {
  const Outcome off = run_fpu(Method::by_name("SERKN2s4"), 0.999 * kPi / kOmega, false);
  EXPECT_FALSE(off.stopped) << off.message;
  EXPECT_GT(off.worst, 1e3);
  const Outcome on = run_fpu(Method::by_name("SERKN2s4"), 0.999 * kPi / kOmega, true);
  EXPECT_TRUE(on.stopped);
  EXPECT_NE(on.message.find("blow-up guard"), std::string::npos) << on.message;
}

// Without a potential the guard watches 1/2|p|^2 + 1/2 q'M q: it stops the blow-up and leaves a
// fine run alone.
TEST(BlowupGuardControl, WithoutAPotentialTheStateNormIsWatched) {
  const Method& strang = Method::by_name("Strang");  // (3 pi: energy error ~4e5 unguarded)
  const Outcome blowup = run_fpu(strang, 3 * kPi / kOmega, true, false);
  EXPECT_TRUE(blowup.stopped);
  EXPECT_NE(blowup.message.find("grew by a factor"), std::string::npos) << blowup.message;
  const Outcome fine = run_fpu(strang, 0.5 / kOmega, true, false);
  EXPECT_FALSE(fine.stopped) << fine.message;
}

}  // namespace
}  // namespace erkn::test
