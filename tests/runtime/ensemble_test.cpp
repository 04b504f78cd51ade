// erkn::Ensemble: every thread count gives the serial result bit for bit, for every method; a
// failing trajectory reports its error and its last completed step without touching the others.
#include <gtest/gtest.h>

#include <atomic>
#include <limits>
#include <stdexcept>

#include "problems.hpp"

namespace erkn::test {
namespace {

constexpr double kH = 0.05, kTEnd = 1.0;
constexpr std::size_t kSize = 9;

// Trajectory i: sine-Gordon (N = 96: circulant M through the FFT; h^2 lambda <= 0.4, below every
// pole) with its own initial data, stiffness and strength of the nonlinearity (parameters).
Member sine_gordon_member(std::size_t i) {
  const int N = 96;
  Member m;
  m.system =
      sine_gordon(Stiffness::circulant(sine_gordon_column(N) * 0.01 * (1 + 0.1 * double(i))));
  const double kappa = 1 + 0.5 * double(i);
  m.system.gradient = [kappa](const Eigen::VectorXd& q, Eigen::VectorXd& g) {
    g = kappa * q.array().sin();
  };
  sine_gordon_initial(N, m.q0, m.p0);
  m.p0 *= 1 + 0.05 * double(i);
  return m;
}

// (One call of step(n): a processed method reads its state, pi, where a call ends.)
TrajectoryResult serial(const Method& method, const Member& m) {
  TrajectoryResult r;
  Integrator run(method, m.system, kH, m.q0, m.p0);
  try {
    run.step(run.steps_until(kTEnd));
  } catch (const Error& e) {
    r.error = e.what();
  }
  r.q = run.q(), r.p = run.p(), r.t = run.t(), r.statistics = run.statistics();
  return r;
}

TEST(Ensemble, EveryThreadCountGivesTheSerialResultBitForBitForEveryMethod) {
  for (const Method& method : Method::all()) {
    SCOPED_TRACE(std::string(method.name()));
    const Ensemble ensemble(method, kH, kSize, sine_gordon_member);
    std::vector<TrajectoryResult> expected(kSize);
    for (std::size_t i = 0; i < kSize; ++i) expected[i] = serial(method, sine_gordon_member(i));
    // Negative control: the trajectories differ, so equality below is not trivial.
    EXPECT_NE(expected[0].q, expected[1].q);
    for (int threads : {1, 2, 3, 8}) {
      const std::vector<TrajectoryResult> got = ensemble.integrate(kTEnd, threads);
      ASSERT_EQ(got.size(), kSize);
      for (std::size_t i = 0; i < kSize; ++i) {
        ASSERT_TRUE(got[i].ok()) << got[i].error;
        EXPECT_EQ(got[i].t, kTEnd);
        EXPECT_EQ(got[i].q, expected[i].q) << "trajectory " << i << ", threads " << threads;
        EXPECT_EQ(got[i].p, expected[i].p) << "trajectory " << i << ", threads " << threads;
        EXPECT_EQ(got[i].statistics.gradient_evaluations,
                  expected[i].statistics.gradient_evaluations);
      }
    }
  }
}

TEST(Ensemble, ARangeGivesTheSameResultsAsTheWholeEnsemble) {
  const Ensemble ensemble(Method::by_name("SERKN2s4"), kH, kSize, sine_gordon_member);
  const auto all = ensemble.integrate(kTEnd, 2);
  const auto part = ensemble.integrate(kTEnd, 3, 7, 2);
  ASSERT_EQ(part.size(), 4u);
  for (std::size_t k = 0; k < part.size(); ++k) EXPECT_EQ(part[k].q, all[3 + k].q);
}

// Trajectory 2: its gradient turns non-finite at the 40th call; 4: q0 and p0 differ in size;
// 6: building the member throws. The others must be the serial results.
Member faulty_member(std::size_t i) {
  if (i == 6) throw std::runtime_error("no such parameter set");
  Member m = sine_gordon_member(i);
  if (i == 2)
    m.system.gradient = [calls = 0](const Eigen::VectorXd& q, Eigen::VectorXd& g) mutable {
      g = q.array().sin();
      if (++calls == 40) g[3] = std::numeric_limits<double>::quiet_NaN();
    };
  if (i == 4) m.p0.conservativeResize(m.p0.size() - 1);
  return m;
}

TEST(Ensemble, AFailingTrajectoryKeepsItsLastStepAndTheOthersTheirResults) {
  const Method& method = Method::by_name("SERKN2s3");
  const Ensemble ensemble(method, kH, kSize, faulty_member);
  const std::vector<TrajectoryResult> got = ensemble.integrate(kTEnd, 2);
  for (std::size_t i : {0, 1, 3, 5, 7, 8}) {
    ASSERT_TRUE(got[i].ok()) << got[i].error;
    EXPECT_EQ(got[i].q, serial(method, faulty_member(i)).q);
  }
  // 2: stopped at the step whose gradient was NaN, with the state of the step before.
  const TrajectoryResult expected = serial(method, faulty_member(2));
  ASSERT_FALSE(expected.error.empty());
  EXPECT_NE(got[2].error.find("trajectory 2"), std::string::npos) << got[2].error;
  EXPECT_NE(got[2].error.find("non-finite"), std::string::npos) << got[2].error;
  EXPECT_GT(got[2].t, 0.0);
  EXPECT_LT(got[2].t, kTEnd);
  EXPECT_EQ(got[2].t, expected.t);
  EXPECT_EQ(got[2].q, expected.q);
  EXPECT_TRUE(got[2].q.allFinite());
  // 4: refused at construction; the result keeps the (inconsistent) initial data.
  EXPECT_NE(got[4].error.find("dimension mismatch"), std::string::npos) << got[4].error;
  EXPECT_EQ(got[4].t, 0.0);
  EXPECT_EQ(got[4].q, faulty_member(4).q0);
  // 6: no member at all.
  EXPECT_NE(got[6].error.find("no such parameter set"), std::string::npos) << got[6].error;
  EXPECT_EQ(got[6].q.size(), 0);
}

TEST(Ensemble, TheObserverSeesEveryStepOfEveryTrajectoryInOrder) {
  const Ensemble ensemble(Method::by_name("SERKN2s4"), kH, kSize, sine_gordon_member);
  std::vector<std::atomic<long>> steps(kSize);
  std::atomic<bool> in_order{true};
  ensemble.integrate(kTEnd, 3, [&](std::size_t i, const Integrator& run) {
    if (run.statistics().steps != ++steps[i]) in_order = false;
  });
  EXPECT_TRUE(in_order);
  for (std::size_t i = 0; i < kSize; ++i) EXPECT_EQ(steps[i], 20);
}

TEST(Ensemble, BadArgumentsAreRefused) {
  const Ensemble ensemble(Method::by_name("SERKN2s4"), kH, kSize, sine_gordon_member);
  EXPECT_THROW(ensemble.integrate(kTEnd, -1), Error);
  EXPECT_THROW(ensemble.integrate(kTEnd, 5, 4), Error);
  EXPECT_THROW(ensemble.integrate(kTEnd, 0, kSize + 1), Error);
  EXPECT_THROW(Ensemble(Method::by_name("SERKN2s4"), kH, 3, nullptr), Error);
  // A t_end before the start is every trajectory's error, not the ensemble's.
  for (const TrajectoryResult& r : ensemble.integrate(-0.5, 2))
    EXPECT_NE(r.error.find("lies before t"), std::string::npos) << r.error;
}

TEST(Ensemble, AListOfMembersIsTheSameAsTheMemberFunction) {
  std::vector<Member> list;
  for (std::size_t i = 0; i < 4; ++i) list.push_back(sine_gordon_member(i));
  const Method& method = Method::by_name("SERKN3s4(1)");
  const auto a = Ensemble(method, kH, list).integrate(kTEnd, 2);
  const auto b = Ensemble(method, kH, 4, sine_gordon_member).integrate(kTEnd, 1);
  for (std::size_t i = 0; i < 4; ++i) EXPECT_EQ(a[i].q, b[i].q);
}

}  // namespace
}  // namespace erkn::test
