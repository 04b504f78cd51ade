#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "erkn/problems.hpp"

namespace erkn::problems {
namespace {

// u0 at the grid point of flat index `flat` (row-major, last axis fastest), in the order of
// operations of the experiments' former 3-D scene (bit-identical data).
double initial_value(Eigen::Index flat, int n, int dims, double dx) {
  const double pi = std::numbers::pi, centre[3] = {0.3, 0.4, 0.5};
  Eigen::Index index[3];
  for (int a = dims - 1; a >= 0; --a, flat /= n) index[a] = flat % n;
  double wave = 2, r2 = 0;
  for (int a = 0; a < dims; ++a) {
    const double x = double(index[a] + 1) * dx;
    wave *= std::sin(pi * x);
    r2 += (x - centre[a]) * (x - centre[a]);
  }
  return wave + std::exp(-100 * r2);
}

}  // namespace

Problem klein_gordon(int n, int dims) {
  if (n < 1 || dims < 1 || dims > 3)
    throw std::invalid_argument("klein_gordon: need n >= 1 points per axis and dims = 1, 2 or 3");
  const double dx = 1.0 / (n + 1);
  Problem p;
  p.key = "KG" + std::to_string(dims) + "D";
  p.title = std::to_string(dims) + "-D Klein-Gordon phi^4, Dirichlet, " + std::to_string(n) + "^" +
            std::to_string(dims);
  p.M = LinearPart::grid(std::vector<GridAxis>(dims, {n, dx, GridAxis::Boundary::dirichlet}), 1.0);
  p.q0.resize(Eigen::Index(std::pow(n, dims)));
  for (Eigen::Index i = 0; i < p.q0.size(); ++i) p.q0[i] = initial_value(i, n, dims, dx);
  p.p0 = Vec::Zero(p.q0.size());
  p.t_error = 1;
  const Potential u = quartic_potential(1);
  p.grad_u = u.grad_u, p.potential = u.potential;  // (no Hessian on a grid)
  p.hessian_vector_u = u.hessian_vector_u;
  return p;
}

}  // namespace erkn::problems
