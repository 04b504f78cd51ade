// With U = 0 an ERKN method is exact for q'' + M q = 0 at any h; its RKN limit is not.
#include <gtest/gtest.h>

#include "problems.hpp"

namespace erkn::test {
namespace {

System free_system(const Stiffness& M) {
  System s;
  s.M = M;
  s.gradient = [](const Eigen::VectorXd&, Eigen::VectorXd& g) { g.setZero(); };
  s.hessian_vector_product = [](const Eigen::VectorXd&, const Eigen::VectorXd& v,
                                Eigen::VectorXd& hv) { hv.setZero(v.size()); };
  return s;
}

// q(t) = cos(t sqrt(M)) q0 + sin(t sqrt(M))/sqrt(M) p0 from an eigendecomposition of M.
Eigen::VectorXd exact(const Eigen::MatrixXd& M, double t, const Eigen::VectorXd& q0,
                      const Eigen::VectorXd& p0) {
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(M);
  const Eigen::ArrayXd w = eig.eigenvalues().cwiseMax(0).array().sqrt();
  const Eigen::ArrayXd c = (w * t).cos();
  Eigen::ArrayXd sinc(w.size());
  for (Eigen::Index k = 0; k < w.size(); ++k) sinc[k] = w[k] == 0 ? t : std::sin(w[k] * t) / w[k];
  const Eigen::MatrixXd& E = eig.eigenvectors();
  return E * (c * (E.transpose() * q0).array() + sinc * (E.transpose() * p0).array()).matrix();
}

struct Case {
  const char* name;
  Stiffness M;
  Eigen::MatrixXd dense;
};

std::vector<Case> cases() {
  const Eigen::MatrixXd D = rotated({0.5, 3.0, 100.0});
  const Eigen::Vector3d diag(0.0, 3.0, 100.0);  // a zero eigenvalue: free motion q0 + t p0
  Eigen::VectorXd col = Eigen::VectorXd::Zero(8);
  col[0] = 60, col[1] = col[7] = -20, col[2] = col[6] = -5;
  return {{"dense", Stiffness::dense(D), D},
          {"diagonal", Stiffness::diagonal(diag), diag.asDiagonal().toDenseMatrix()},
          {"circulant", Stiffness::circulant(col), Stiffness::circulant(col).to_dense(8)}};
}

double relative_error_after(const Method& m, const Case& c, double h, int steps) {
  const Eigen::Index d = c.dense.rows();
  Eigen::VectorXd q0 = Eigen::VectorXd::LinSpaced(d, 1.0, -0.5), p0 = Eigen::VectorXd::Ones(d);
  Integrator run(m, free_system(c.M), h, q0, p0);
  for (int k = 0; k < steps; ++k) run.step();
  const Eigen::VectorXd ref = exact(c.dense, steps * h, q0, p0);
  return (run.q() - ref).norm() / ref.norm();
}

TEST(Exactness, ErknMethodsAreExactWithoutNonlinearityEvenAtHOmega50) {
  for (const Case& c : cases()) {
    const double omega_max = std::sqrt(c.M.eigenvalues().maxCoeff());
    for (double h_omega : {0.5, 5.0, 50.0})
      for (const Method& m : methods_of(Kind::erkn)) {
        SCOPED_TRACE(std::string(m.name()) + " " + c.name +
                     " h*omega_max = " + std::to_string(h_omega));
        EXPECT_LE(relative_error_after(m, c, h_omega / omega_max, 40), 1e-12);
      }
  }
}

TEST(Exactness, RknLimitsAreNotExactAtHOmega50) {
  for (const Case& c : cases()) {
    if (c.M.eigenvalues().minCoeff() == 0) continue;  // free motion would dominate the norm
    const double h = 50 / std::sqrt(c.M.eigenvalues().maxCoeff());
    for (const Method& m : methods_of(Kind::rkn)) {
      SCOPED_TRACE(std::string(m.name()) + " " + c.name);
      const double err = relative_error_after(m, c, h, 40);
      EXPECT_FALSE(err <= 1e-2) << "relative error " << err;
    }
  }
}

}  // namespace
}  // namespace erkn::test
