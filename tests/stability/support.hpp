// Helpers shared by the stability tests: the scalar test equation y'' + omega^2 y = -eps y run
// through erkn::Integrator, and points picked from the computed regions.
#pragma once

#include <cmath>
#include <erkn/erkn.hpp>
#include <erkn/stability.hpp>
#include <functional>
#include <optional>
#include <vector>

namespace erkn::test {

/// The test equation at (V, z) with step h: M = omega^2 = V / h^2, grad U(y) = eps y, eps = z / h^2
/// (with its exact Hessian, so the Newton fallback solves the linear stage equation exactly).
inline System test_equation(double V, double z, double h) {
  const double eps = z / (h * h);
  System sys;
  sys.M = Stiffness::scalar(V / (h * h));
  sys.gradient = [eps](const Eigen::VectorXd& q, Eigen::VectorXd& g) { g = eps * q; };
  sys.hessian = [eps](const Eigen::VectorXd&, Eigen::MatrixXd& H) { H.setConstant(eps); };
  return sys;
}

inline Eigen::VectorXd scalar(double x) { return Eigen::VectorXd::Constant(1, x); }

/// S measured from one integrator step per column: (q1, h p1) from (q0, h p0) = e_1, e_2.
inline StabilityMatrix one_step_matrix(const Method& m, double V, double z, double h,
                                       const Options& o = {}) {
  Integrator a(m, test_equation(V, z, h), h, scalar(1), scalar(0), o);
  a.step();
  Integrator b(m, test_equation(V, z, h), h, scalar(0), scalar(1 / h), o);
  b.step();
  return {a.q()[0], b.q()[0], h * a.p()[0], h * b.p()[0]};
}

/// Grid points satisfying pred, whose 8 grid neighbours satisfy pred too ("well inside").
inline std::vector<StabilityPoint> interior_points(
    const StabilityGrid& g, const std::function<bool(const StabilityPoint&)>& pred) {
  std::vector<StabilityPoint> out;
  for (int i = 1; i + 1 < g.nv; ++i)
    for (int j = 1; j + 1 < g.nz; ++j) {
      bool ok = true;
      for (int di = -1; di <= 1 && ok; ++di)
        for (int dj = -1; dj <= 1 && ok; ++dj) ok = pred(g.point(i + di, j + dj));
      if (ok) out.push_back(g.point(i, j));
    }
  return out;
}

/// True when V is at least rel * pole away from every pole of m.
inline bool away_from_poles(const Method& m, double V, double rel) {
  for (double p : m.poles())
    if (std::abs(V - p) < rel * p) return false;
  return true;
}

}  // namespace erkn::test
