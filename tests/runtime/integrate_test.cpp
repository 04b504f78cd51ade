// integrate(t_end, observer) on the grid takes whole steps, reports every one, and matches step()
// (off-grid ends and output times: output_test.cpp).
#include <gtest/gtest.h>

#include "problems.hpp"

namespace erkn::test {
namespace {

TEST(Integrate, ObserverSeesEveryStepAndTheResultEqualsSteppingByHand) {
  const Method& m = Method::by_name("SERKN2s4");
  const Eigen::Vector3d q0(0.6, -0.4, 0.3), p0(0.2, 0.5, -0.7);
  Integrator a(m, polynomial_system(), 0.1, q0, p0), b(m, polynomial_system(), 0.1, q0, p0);
  std::vector<double> times;
  a.integrate(3.0, [&](double t, const Eigen::VectorXd& q, const Eigen::VectorXd&) {
    times.push_back(t);
    EXPECT_EQ(q.size(), 3);
  });
  ASSERT_EQ(times.size(), 30u);
  for (size_t k = 0; k < times.size(); ++k) EXPECT_DOUBLE_EQ(times[k], 0.1 * double(k + 1));
  for (int k = 0; k < 30; ++k) b.step();
  EXPECT_EQ(a.q(), b.q());
  EXPECT_EQ(a.p(), b.p());
  EXPECT_EQ(a.t(), 3.0);
  EXPECT_EQ(a.statistics().steps, 30);
  EXPECT_GE(a.statistics().gradient_evaluations, 30 * m.stages());
}

TEST(Integrate, SetStateAndSetStepSizeRestartFromTheNewValues) {
  const Method& m = Method::by_name("SERKN2s4");
  const Eigen::Vector3d q0(0.6, -0.4, 0.3), p0(0.2, 0.5, -0.7);
  Integrator a(m, polynomial_system(), 0.1, q0, p0), b(m, polynomial_system(), 0.05, q0, p0);
  a.integrate(1.0);
  a.set_state(q0, p0, 0.0);
  a.set_step_size(0.05);
  a.integrate(1.0);
  b.integrate(1.0);
  EXPECT_EQ(a.q(), b.q());
  EXPECT_EQ(a.t(), 1.0);
}

}  // namespace
}  // namespace erkn::test
