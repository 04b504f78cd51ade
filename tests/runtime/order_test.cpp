// Observed order of every method on a nonlinear problem with a dense, non-diagonal M whose
// Hessian does not commute with it, against a long-double RK4 reference (a different method,
// accurate to ~1e-17).
#include <gtest/gtest.h>

#include <cstdio>

#include "problems.hpp"

namespace erkn::test {
namespace {

constexpr double kT = 2.0;
const Eigen::Vector3d kQ(0.6, -0.4, 0.3), kP(0.2, 0.5, -0.7);

// Stage equations solved to round-off (tolerance 0): the default tolerance 1e-14 per stage adds
// errors up to ~1e-11 at n ~ 450 steps (RKN2s4), above the floor.
Options solved_to_round_off() {
  Options o;
  o.tolerance = 0;
  return o;
}

TEST(Order, ReferenceIsAccurateTo1e15) {
  EXPECT_LT(polynomial_reference(kQ, kP, {kT}).accuracy, 1e-15);
}

// Negative control: the same method with d_1 and bbar_1 nudged by 5% (perturbed()) shows a
// slope at least 0.5 below its order on the same step sizes.
//
// A processed method (psi = pi o K o pi^-1) runs over 10 kT: its global error is pi's error at
// the ends, which does not grow, plus the accumulated O(h^order) part, and over kT the first is
// still comparable (PMLF6: local slopes 6.52 -> 6.36 at errors 2e-10 .. 3e-14 over kT, 6.07 ->
// 6.01 over 10 kT; OMF6(5F3G) 6.04 -> 6.00 over either).
TEST(Order, ObservedOrderOfEveryMethodIsWithin015OfItsCertifiedOrder) {
  const Eigen::Vector3d ref = polynomial_reference(kQ, kP, {kT}).q[0];
  const Eigen::Vector3d ref_long = polynomial_reference(kQ, kP, {10 * kT}).q[0];
  auto error_of = [&](const Method& m) {
    const double T = m.is_processed() ? 10 * kT : kT;
    return [&ref, &ref_long, m, T](long n) {  // (h = kT / n either way)
      Integrator run(m, polynomial_system(), kT / double(n), kQ, kP, solved_to_round_off());
      run.integrate(T);
      return (run.q() - (m.is_processed() ? ref_long : ref)).norm();
    };
  };
  for (const Method& m : Method::all()) {
    SCOPED_TRACE(std::string(m.name()));
    const ObservedOrder o = observed_order(error_of(m));
    ASSERT_GE(o.n.size(), 3u) << "too few step sizes with an error above " << kOrderFloor;
    std::vector<double> perturbed_error;
    for (long n : o.n) perturbed_error.push_back(error_of(perturbed(m))(n));
    const double perturbed_slope = fitted_slope(o.n, perturbed_error);
    std::printf(
        "%-14s certified order %d: observed %.3f (h = T/%ld..T/%ld, error %.1e..%.1e); "
        "nudged d_1, bbar_1: %.2f\n",
        std::string(m.name()).c_str(), m.order(), o.slope, o.n.front(), o.n.back(), o.error.front(),
        o.error.back(), perturbed_slope);
    EXPECT_NEAR(o.slope, m.order(), 0.15);
    EXPECT_LT(perturbed_slope, m.order() - 0.5);
  }
}

}  // namespace
}  // namespace erkn::test
