// The one-step map is symplectic: J^T Omega J = Omega for its Jacobian J (fourth-order central
// differences), for every method at several h; a method with one coefficient nudged is not.
#include <gtest/gtest.h>

#include "problems.hpp"

namespace erkn::test {
namespace {

double defect(const Method& m, double h) {
  Eigen::VectorXd y(6);
  y << 0.6, -0.4, 0.3, 0.2, 0.5, -0.7;
  return symplecticity_defect(m, polynomial_system(), h, y);
}

TEST(Symplecticity, OneStepMapOfEveryMethodPreservesOmega) {
  for (const Method& m : Method::all())
    for (double h : {0.05, 0.2, 0.5}) {
      SCOPED_TRACE(std::string(m.name()) + " h = " + std::to_string(h));
      EXPECT_LE(defect(m, h), 1e-9);
    }
}

TEST(Symplecticity, NudgingOneCoefficientBreaksItByOrdersOfMagnitude) {
  for (const Method& m : Method::all())
    for (double h : {0.05, 0.2, 0.5}) {
      if (m.is_explicit()) continue;  // the nudged coefficient is one the explicit path never reads
      SCOPED_TRACE(std::string(m.name()) + " h = " + std::to_string(h));
      EXPECT_GE(defect(perturbed(m), h), 1e-6);
    }
}

}  // namespace
}  // namespace erkn::test
