#include "grid_problems.hpp"

#include <cmath>
#include <numbers>
#include <string>

namespace ex {

Problem sine_gordon_2d(int n) {
  const double L = 12, dx = L / n;
  Problem p;
  p.key = "SG2D";
  p.title = "2-D sine-Gordon, periodic, " + std::to_string(n) + "^2";
  p.M = LinearPart::grid(
      {{n, dx, GridAxis::Boundary::periodic}, {n, dx, GridAxis::Boundary::periodic}}, 0.0);
  p.q0.resize(n * n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double x = -L / 2 + i * dx, y = -L / 2 + j * dx;
      p.q0[i * n + j] = 2.5 * std::exp(-(x * x + y * y));
    }
  p.p0 = Vec::Zero(n * n);
  p.t_error = 1;
  p.grad_u = [](const Vec& q, Vec& g) { g = q.array().sin(); };
  p.potential = [](const Vec& q) { return -q.array().cos().sum(); };
  return p;
}

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
