// The scalar, diagonal, circulant and dense forms of the same M give the same trajectory.
#include <gtest/gtest.h>

#include "problems.hpp"

namespace erkn::test {
namespace {

// max |(q, p)_a - (q, p)_b| / max |(q, p)_a| over 50 steps of q'' + M q = -sin q.
double max_difference(const Method& m, const Stiffness& a, const Stiffness& b, double h,
                      const Eigen::VectorXd& q0, const Eigen::VectorXd& p0) {
  Integrator ra(m, sine_gordon(a), h, q0, p0), rb(m, sine_gordon(b), h, q0, p0);
  double diff = 0;
  for (int n = 0; n < 50; ++n) {
    ra.step(), rb.step();
    const double scale = std::max(ra.q().cwiseAbs().maxCoeff(), ra.p().cwiseAbs().maxCoeff());
    diff = std::max({diff, (ra.q() - rb.q()).cwiseAbs().maxCoeff() / scale,
                     (ra.p() - rb.p()).cwiseAbs().maxCoeff() / scale});
  }
  return diff;
}

TEST(StructureAgreement, ScalarDiagonalCirculantAndDenseAgreeForOmegaSquaredTimesIdentity) {
  const int d = 6;
  const double w2 = 30;
  Eigen::VectorXd col = Eigen::VectorXd::Zero(d);
  col[0] = w2;
  const Stiffness forms[] = {
      Stiffness::scalar(w2), Stiffness::diagonal(Eigen::VectorXd::Constant(d, w2)),
      Stiffness::circulant(col), Stiffness::dense(w2 * Eigen::MatrixXd::Identity(d, d))};
  Eigen::VectorXd q0 = Eigen::VectorXd::LinSpaced(d, -1, 2),
                  p0 = Eigen::VectorXd::LinSpaced(d, 1, 0);
  for (const Method& m : Method::all())
    for (int k = 1; k < 4; ++k) {
      SCOPED_TRACE(std::string(m.name()) + " form " + std::to_string(k));
      EXPECT_LE(max_difference(m, forms[0], forms[k], 0.1, q0, p0), 1e-13);
    }
}

TEST(StructureAgreement, DiagonalAndDenseAgree) {
  const Eigen::VectorXd diag = Eigen::VectorXd::LinSpaced(5, 0.0, 40.0);
  Eigen::VectorXd q0 = Eigen::VectorXd::LinSpaced(5, 1, -1), p0 = Eigen::VectorXd::Ones(5);
  for (const Method& m : Method::all()) {
    SCOPED_TRACE(std::string(m.name()));
    EXPECT_LE(max_difference(m, Stiffness::diagonal(diag),
                             Stiffness::dense(diag.asDiagonal().toDenseMatrix()), 0.1, q0, p0),
              1e-13);
  }
}

TEST(StructureAgreement, CirculantStencilCirculantFftAndDenseAgreeOnSineGordon) {
  const int N = 16;
  Eigen::VectorXd q0, p0;
  sine_gordon_initial(N, q0, p0);
  const Eigen::VectorXd stencil = sine_gordon_column(N);
  // A first column with every entry nonzero, so M is applied through the FFT.
  Eigen::VectorXd full(N);
  for (int j = 0; j < N; ++j) full[j] = 1.0 / (1 + std::min(j, N - j));
  full[0] = 3;
  for (const Eigen::VectorXd& col : {stencil, full})
    for (const Method& m : Method::all()) {
      SCOPED_TRACE(std::string(m.name()) + (col[2] == 0 ? " stencil" : " full column"));
      const Stiffness circ = Stiffness::circulant(col);
      EXPECT_LE(max_difference(m, circ, Stiffness::dense(circ.to_dense(N)), 1.0 / 40, q0, p0),
                1e-13);
    }
}

}  // namespace
}  // namespace erkn::test
