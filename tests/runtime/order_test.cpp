// Observed order of every method on a nonlinear problem with a dense, non-diagonal M whose
// Hessian does not commute with it, against an RK4 reference (a different method).
#include <gtest/gtest.h>

#include "problems.hpp"

namespace erkn::test {
namespace {

constexpr double kT = 2.0;

struct Reference {
  Eigen::VectorXd q0, p0, q;
};

const Reference& reference() {
  static const Reference ref = [] {
    Reference r;
    r.q0 = Eigen::Vector3d(0.6, -0.4, 0.3);
    r.p0 = Eigen::Vector3d(0.2, 0.5, -0.7);
    const System s = polynomial_system();
    Eigen::VectorXd q = r.q0, p = r.p0, q2 = r.q0, p2 = r.p0;
    rk4(s, s.M.matrix(), kT, 40000, q, p);
    rk4(s, s.M.matrix(), kT, 80000, q2, p2);
    EXPECT_LT((q - q2).norm(), 1e-14) << "the RK4 reference is not converged";
    r.q = q2;
    return r;
  }();
  return ref;
}

// The fit uses the four finest of h = T/10, T/20, ..., T/2560 whose error is at least 3e-13
// (30 times the reference's accuracy): coarse steps can still be dominated by the next order's
// term (SERKN2s3 shows slope 3.7 at h = T/20..T/160 and 3.0 from T/320 on).
TEST(Order, ObservedOrderOfEveryMethodIsWithin015OfItsClaimedOrder) {
  const Reference& ref = reference();
  for (const Method& m : Method::all()) {
    SCOPED_TRACE(std::string(m.name()));
    std::vector<double> x, y;  // log h, log error
    for (int n = 10; n <= 2560; n *= 2) {
      Integrator run(m, polynomial_system(), kT / n, ref.q0, ref.p0);
      run.integrate(kT);
      const double err = (run.q() - ref.q).norm();
      if (err < 3e-13) break;
      x.push_back(std::log(kT / n)), y.push_back(std::log(err));
    }
    ASSERT_GE(x.size(), 4u) << "too few step sizes above the reference's accuracy";
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (size_t i = x.size() - 4; i < x.size(); ++i)
      sx += x[i], sy += y[i], sxx += x[i] * x[i], sxy += x[i] * y[i];
    const double slope = (4 * sxy - sx * sy) / (4 * sxx - sx * sx);
    EXPECT_NEAR(slope, m.order(), 0.15);
  }
}

}  // namespace
}  // namespace erkn::test
