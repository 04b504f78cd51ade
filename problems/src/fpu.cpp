#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "erkn/problems.hpp"

namespace erkn::problems {
namespace {

// The spring elongation u_i (i = 0..m) of the chain (HLW section I.5.1) at q = (x0, x1), for
// any scalar type (double for the runtime, long double for the reference force):
//   u_0 = x0_1 - x1_1,  u_i = x0_{i+1} - x1_{i+1} - x0_i - x1_i,  u_m = x0_m + x1_m.
template <class V>
auto elongation(const V& q, int m, int i) {
  if (i == 0) return q[0] - q[m];
  if (i == m) return q[m - 1] + q[2 * m - 1];
  return q[i] - q[m + i] - q[i - 1] - q[m + i - 1];
}

// g += w grad u_i: u_i depends on x0_i, x1_i (+, -) and x0_{i-1}, x1_{i-1} (-, -).
template <class V, class W>
void add_spring(V& g, int m, int i, W w) {
  if (i < m) g[i] += w, g[m + i] -= w;
  if (i > 0) g[i - 1] += i == m ? w : -w, g[m + i - 1] += i == m ? w : -w;
}

// The d x (m + 1) matrix whose column i is grad u_i (u is linear in q).
Eigen::MatrixXd elongation_gradients(int m) {
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(2 * m, m + 1);
  for (int i = 0; i <= m; ++i) {
    Eigen::VectorXd g = Eigen::VectorXd::Zero(2 * m);
    add_spring(g, m, i, 1.0);
    G.col(i) = g;
  }
  return G;
}

// The stiff springs' energies I_j = (x1_j'^2 + omega^2 x1_j^2) / 2 and their sum I.
std::vector<Invariant> oscillatory_energies(int m, double omega) {
  const auto energy = [m, omega](const Vec& q, const Vec& p, int j) {
    return 0.5 * (p[m + j] * p[m + j] + omega * omega * q[m + j] * q[m + j]);
  };
  std::vector<Invariant> out;
  for (int j = 0; j < m; ++j)
    out.push_back({"I_" + std::to_string(j + 1),
                   [energy, j](const Vec& q, const Vec& p) { return energy(q, p, j); }, false});
  out.push_back({"I",
                 [energy, m](const Vec& q, const Vec& p) {
                   double sum = 0;
                   for (int j = 0; j < m; ++j) sum += energy(q, p, j);
                   return sum;
                 },
                 false});
  return out;
}

}  // namespace

Potential fpu_potential(int m) {
  if (m < 1) throw std::invalid_argument("fpu: need m >= 1 stiff springs");
  Potential u;
  // (no allocation: the elongations one at a time)
  u.grad_u = [m](const Vec& q, Vec& g) {
    g.setZero(2 * m);
    for (int i = 0; i <= m; ++i) {
      const double u = elongation(q, m, i);
      add_spring(g, m, i, u * u * u);
    }
  };
  u.potential = [m](const Vec& q) {
    double U = 0;
    for (int i = 0; i <= m; ++i) U += std::pow(elongation(q, m, i), 4);
    return 0.25 * U;
  };
  u.hessian_u = [m, G = elongation_gradients(m)](const Vec& q) {
    Vec w(m + 1);
    for (int i = 0; i <= m; ++i) w[i] = 3 * std::pow(elongation(q, m, i), 2);
    return Eigen::MatrixXd(G * w.asDiagonal() * G.transpose());
  };
  // Hess U v = sum_i 3 u_i^2 (grad u_i . v) grad u_i (u is linear in q).
  u.hessian_vector_u = [m](const Vec& q, const Vec& v, Vec& hv) {
    hv.setZero(2 * m);
    for (int i = 0; i <= m; ++i) {
      const double u = elongation(q, m, i);
      add_spring(hv, m, i, 3 * u * u * elongation(v, m, i));
    }
  };
  return u;
}

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
  const Potential u = fpu_potential(m);
  p.grad_u = u.grad_u, p.potential = u.potential, p.hessian_u = u.hessian_u;
  p.hessian_vector_u = u.hessian_vector_u;
  p.force_ld = [m, omega](const VecLD& q, VecLD& f) {
    f.assign(2 * m, 0.0L);
    for (int i = 0; i <= m; ++i) {
      const long double u = elongation(q, m, i);
      add_spring(f, m, i, u * u * u);
    }
    const long double w2 = (long double)omega * omega;
    for (int i = 0; i < 2 * m; ++i) f[i] = -f[i] - (i >= m ? w2 * q[i] : 0.0L);
  };
  p.adiabatic = oscillatory_energies(m, omega);
  return p;
}

}  // namespace erkn::problems
