// The one-step map is symplectic: J^T Omega J = Omega for its Jacobian J (fourth-order central
// differences), for every method at several h; a method with one coefficient nudged is not.
#include <gtest/gtest.h>

#include "problems.hpp"

namespace erkn::test {
namespace {

Eigen::VectorXd one_step(const Method& m, double h, const Eigen::VectorXd& y) {
  const Eigen::Index d = y.size() / 2;
  Options o;
  o.tolerance = 1e-16;  // iterate the stages to round-off: the map must be smooth at 1e-13
  Integrator run(m, polynomial_system(), h, y.head(d), y.tail(d), o);
  run.step();
  Eigen::VectorXd out(2 * d);
  out << run.q(), run.p();
  return out;
}

double symplecticity_defect(const Method& m, double h) {
  const int d = 3;
  Eigen::VectorXd y(2 * d);
  y << 0.6, -0.4, 0.3, 0.2, 0.5, -0.7;
  const double e = 1e-3;
  Eigen::MatrixXd J(2 * d, 2 * d);
  for (int j = 0; j < 2 * d; ++j) {
    auto at = [&](double k) {
      Eigen::VectorXd z = y;
      z[j] += k * e;
      return one_step(m, h, z);
    };
    J.col(j) = (8 * (at(1) - at(-1)) - (at(2) - at(-2))) / (12 * e);
  }
  Eigen::MatrixXd Omega = Eigen::MatrixXd::Zero(2 * d, 2 * d);
  Omega.topRightCorner(d, d).setIdentity();
  Omega.bottomLeftCorner(d, d) = -Eigen::MatrixXd::Identity(d, d);
  return (J.transpose() * Omega * J - Omega).cwiseAbs().maxCoeff();
}

TEST(Symplecticity, OneStepMapOfEveryMethodPreservesOmega) {
  for (const Method& m : Method::all())
    for (double h : {0.05, 0.2, 0.5}) {
      SCOPED_TRACE(std::string(m.name()) + " h = " + std::to_string(h));
      EXPECT_LE(symplecticity_defect(m, h), 1e-9);
    }
}

TEST(Symplecticity, NudgingOneCoefficientBreaksItByOrdersOfMagnitude) {
  for (const Method& m : Method::all())
    for (double h : {0.05, 0.2, 0.5}) {
      if (m.is_explicit()) continue;  // the nudged coefficient is one the explicit path never reads
      SCOPED_TRACE(std::string(m.name()) + " h = " + std::to_string(h));
      EXPECT_GE(symplecticity_defect(perturbed(m), h), 1e-6);
    }
}

}  // namespace
}  // namespace erkn::test
