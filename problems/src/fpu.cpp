#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "erkn/problems.hpp"

namespace erkn::problems {
namespace {

// The spring elongations u_0..u_m of the chain (HLW section I.5.1) at q = (x0, x1), for any
// scalar type (double for the runtime, long double for the reference force).
template <class V>
V elongations(const V& q, int m) {
  V u(m + 1);
  u[0] = q[0] - q[m];
  for (int i = 1; i < m; ++i) u[i] = q[i] - q[m + i] - q[i - 1] - q[m + i - 1];
  u[m] = q[m - 1] + q[2 * m - 1];
  return u;
}

// g += sum_i w_i grad u_i: u_i depends on x0_i, x1_i (+, -) and x0_{i-1}, x1_{i-1} (-, -).
template <class V, class W>
void add_transposed(const W& w, int m, V& g) {
  g[0] += w[0], g[m] -= w[0];
  for (int i = 1; i < m; ++i)
    g[i] += w[i], g[m + i] -= w[i], g[i - 1] -= w[i], g[m + i - 1] -= w[i];
  g[m - 1] += w[m], g[2 * m - 1] += w[m];
}

// The d x (m + 1) matrix whose column i is grad u_i (u is linear in q).
Eigen::MatrixXd elongation_gradients(int m) {
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(2 * m, m + 1);
  for (int i = 0; i <= m; ++i) {
    Eigen::VectorXd e = Eigen::VectorXd::Zero(m + 1), g = Eigen::VectorXd::Zero(2 * m);
    e[i] = 1;
    add_transposed(e, m, g);
    G.col(i) = g;
  }
  return G;
}

}  // namespace

Problem fpu(int m, double omega) {
  if (m < 1 || !std::isfinite(omega) || omega <= 0)
    throw std::invalid_argument("fpu: need m >= 1 stiff springs and a finite omega > 0");
  Problem p;
  p.key = "FPU";
  char title[64];
  std::snprintf(title, sizeof title, "Fermi-Pasta-Ulam, m = %d, omega = %g", m, omega);
  p.title = title;
  Vec diag(2 * m);
  diag << Vec::Zero(m), Vec::Constant(m, omega * omega);
  p.M = LinearPart::diagonal(diag);
  p.q0 = Vec::Zero(2 * m), p.p0 = Vec::Zero(2 * m);
  p.q0[0] = 1, p.p0[0] = 1, p.q0[m] = 1 / omega, p.p0[m] = 1;
  p.t_error = 10;
  p.h_energy = 1 / omega;
  p.grad_u = [m](const Vec& q, Vec& g) {
    g.setZero(2 * m);
    add_transposed(Vec(elongations(q, m).array().cube()), m, g);
  };
  p.potential = [m](const Vec& q) { return 0.25 * elongations(q, m).array().pow(4).sum(); };
  p.hessian_u = [m, G = elongation_gradients(m)](const Vec& q) {
    const Vec w = 3 * elongations(q, m).array().square();
    return Eigen::MatrixXd(G * w.asDiagonal() * G.transpose());
  };
  p.force_ld = [m, omega](const VecLD& q, VecLD& f) {
    const VecLD u = elongations(q, m);
    VecLD c(u.size());
    for (size_t i = 0; i < u.size(); ++i) c[i] = u[i] * u[i] * u[i];
    f.assign(2 * m, 0.0L);
    add_transposed(c, m, f);
    const long double w2 = (long double)omega * omega;
    for (int i = 0; i < 2 * m; ++i) f[i] = -f[i] - (i >= m ? w2 * q[i] : 0.0L);
  };
  return p;
}

}  // namespace erkn::problems
