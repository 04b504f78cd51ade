#include "grid_problems.hpp"

#include <cmath>
#include <numbers>
#include <string>

namespace ex {

Problem klein_gordon_3d(int n) {
  const double pi = std::numbers::pi, dx = 1.0 / (n + 1);
  Problem p;
  p.key = "KG3D";
  p.title = "3-D Klein-Gordon phi^4, Dirichlet, " + std::to_string(n) + "^3";
  const GridAxis axis{n, dx, GridAxis::Boundary::dirichlet};
  p.M = LinearPart::grid({axis, axis, axis}, 1.0);
  p.q0.resize(Eigen::Index(n) * n * n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        const double x = (i + 1) * dx, y = (j + 1) * dx, z = (k + 1) * dx;
        const double r2 = (x - 0.3) * (x - 0.3) + (y - 0.4) * (y - 0.4) + (z - 0.5) * (z - 0.5);
        p.q0[(Eigen::Index(i) * n + j) * n + k] =
            2 * std::sin(pi * x) * std::sin(pi * y) * std::sin(pi * z) + std::exp(-100 * r2);
      }
  p.p0 = Vec::Zero(p.q0.size());
  p.t_error = 1;
  p.grad_u = [](const Vec& q, Vec& g) { g = q.array().cube(); };
  p.potential = [](const Vec& q) { return 0.25 * q.array().square().square().sum(); };
  return p;
}

}  // namespace ex
