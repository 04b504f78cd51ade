// Test problems and helpers shared by the runtime tests.
#pragma once

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <erkn/erkn.hpp>
#include <erkn/problems.hpp>
#include <functional>
#include <string>
#include <vector>

namespace erkn::test {

inline std::vector<Method> methods_of(Kind kind) {
  std::vector<Method> out;
  for (const Method& m : Method::all())
    if (m.kind() == kind) out.push_back(m);
  return out;
}

/// A dense, non-diagonal 3x3 M with eigenvalues `lambda` (rotated by a fixed orthogonal matrix).
inline Eigen::MatrixXd rotated(const Eigen::Vector3d& lambda) {
  Eigen::Matrix3d Q =
      Eigen::Matrix3d(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  return Q * lambda.asDiagonal() * Q.transpose();
}

/// q'' + M q = -grad U, d = 3, M dense non-diagonal, U a polynomial with cross terms whose
/// Hessian does not commute with M:  U = eps (q1^2 q2 + q2 q3^2 + q1 q2 q3) + (q1^4+q2^4+q3^4)/4.
inline System polynomial_system(double eps = 0.5) {
  System s;
  s.M = Stiffness::dense(rotated({1.0, 2.5, 6.0}));
  s.gradient = [eps](const Eigen::VectorXd& q, Eigen::VectorXd& g) {
    g[0] = eps * (2 * q[0] * q[1] + q[1] * q[2]) + q[0] * q[0] * q[0];
    g[1] = eps * (q[0] * q[0] + q[2] * q[2] + q[0] * q[2]) + q[1] * q[1] * q[1];
    g[2] = eps * (2 * q[1] * q[2] + q[0] * q[1]) + q[2] * q[2] * q[2];
  };
  s.potential = [eps](const Eigen::VectorXd& q) {
    return eps * (q[0] * q[0] * q[1] + q[1] * q[2] * q[2] + q[0] * q[1] * q[2]) +
           0.25 * q.array().pow(4).sum();
  };
  s.hessian = [eps](const Eigen::VectorXd& q, Eigen::MatrixXd& H) {
    H << eps * 2 * q[1] + 3 * q[0] * q[0], eps * (2 * q[0] + q[2]), eps * q[1],
        eps * (2 * q[0] + q[2]), 3 * q[1] * q[1], eps * (2 * q[2] + q[0]), eps * q[1],
        eps * (2 * q[2] + q[0]), eps * 2 * q[1] + 3 * q[2] * q[2];
  };
  return s;
}

/// Classical RK4 on (q, p)' = (p, -M q - grad U(q)): the independent reference.
inline void rk4(const System& s, const Eigen::MatrixXd& M, double T, long n, Eigen::VectorXd& q,
                Eigen::VectorXd& p) {
  const double h = T / double(n);
  Eigen::VectorXd g(q.size());
  auto acc = [&](const Eigen::VectorXd& x) {
    s.gradient(x, g);
    return Eigen::VectorXd(-M * x - g);
  };
  for (long k = 0; k < n; ++k) {
    Eigen::VectorXd k1q = p, k1p = acc(q);
    Eigen::VectorXd k2q = p + 0.5 * h * k1p, k2p = acc(q + 0.5 * h * k1q);
    Eigen::VectorXd k3q = p + 0.5 * h * k2p, k3p = acc(q + 0.5 * h * k2q);
    Eigen::VectorXd k4q = p + h * k3p, k4p = acc(q + h * k3q);
    q += h / 6 * (k1q + 2 * k2q + 2 * k3q + k4q);
    p += h / 6 * (k1p + 2 * k2p + 2 * k3p + k4p);
  }
}

/// Sine-Gordon, problem 1, from the problems library: its circulant M's first column, the system
/// with another M (a dense copy, a scaled stencil), and the initial values.
inline Eigen::VectorXd sine_gordon_column(int N) { return problems::sine_gordon(N).M.column; }

inline System sine_gordon(const Stiffness& M) {
  // grad U, U and its Hessian act pointwise: any N serves (a scalar M has dim() == 0).
  System s = problems::system(problems::sine_gordon(2));
  s.M = M;
  return s;
}

inline void sine_gordon_initial(int N, Eigen::VectorXd& q, Eigen::VectorXd& p) {
  const problems::Problem pr = problems::sine_gordon(N);
  q = pr.q0;
  p = pr.p0;
}

/// A copy of a method with one coefficient nudged: bbar_1 *= 1 + kNudge (breaks symplecticity).
inline constexpr double kNudge = 5e-2;
inline const generated::Table* nudged_original = nullptr;
inline void nudged_coefficients(double v, double* b, double* bbar, double* abar) {
  nudged_original->coefficients(v, b, bbar, abar);
  bbar[0] *= 1 + kNudge;
}
/// Valid until the next call (one perturbed method at a time).
inline Method perturbed(const Method& m) {
  static generated::Table copy;
  nudged_original = &m.table();
  copy = m.table();
  copy.coefficients = nudged_coefficients;
  return Method(m.id(), &copy);
}

}  // namespace erkn::test
