// The RKF7(8) long-double reference, checked where the exact solution is known (P2).
#include <gtest/gtest.h>

#include "problem.hpp"

namespace ex {
namespace {

TEST(Reference, AgreesWithTheExactDuffingSolution) {
  Problem p = duffing();
  const Vec exact = (*p.exact)(10);
  p.exact.reset();
  const Reference r = reference_solution(p, 10, 1e-14);
  EXPECT_GT(r.steps, 0);
  EXPECT_LE(r.accuracy, 1e-14);
  EXPECT_LT((r.q - exact).lpNorm<Eigen::Infinity>(), 1e-13);
}

TEST(Reference, SineGordonReachesItsStatedAccuracy) {
  const Reference r = reference_solution(sine_gordon(32), 10, 1e-13);
  EXPECT_LE(r.accuracy, 1e-13);
  EXPECT_EQ(r.q.size(), 32);
}

}  // namespace
}  // namespace ex
