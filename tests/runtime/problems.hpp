// Test problems and helpers shared by the runtime tests.
#pragma once

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <erkn/erkn.hpp>
#include <erkn/problems.hpp>
#include <functional>
#include <random>
#include <string>
#include <vector>

namespace erkn::test {

/// FPU with stiff springs omega = kStiffOmega (erkn::problems::fpu(3, 50)), made once: the
/// scene of the advisor's, its trial run's and the blow-up guard's tests.
inline constexpr double kStiffOmega = 50;
inline const problems::Problem& stiff_fpu() {
  static const problems::Problem p = problems::fpu(3, kStiffOmega);
  return p;
}

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

/// grad U of polynomial_system below, for any scalar type (double, and long double for the
/// reference solution).
template <class T>
Eigen::Matrix<T, 3, 1> polynomial_gradient(const Eigen::Matrix<T, 3, 1>& q, T eps) {
  return {eps * (2 * q[0] * q[1] + q[1] * q[2]) + q[0] * q[0] * q[0],
          eps * (q[0] * q[0] + q[2] * q[2] + q[0] * q[2]) + q[1] * q[1] * q[1],
          eps * (2 * q[1] * q[2] + q[0] * q[1]) + q[2] * q[2] * q[2]};
}

/// q'' + M q = -grad U, d = 3, M dense non-diagonal, U a polynomial with cross terms whose
/// Hessian does not commute with M:  U = eps (q1^2 q2 + q2 q3^2 + q1 q2 q3) + (q1^4+q2^4+q3^4)/4.
inline System polynomial_system(double eps = 0.5) {
  System s;
  s.M = Stiffness::dense(rotated({1.0, 2.5, 6.0}));
  s.gradient = [eps](const Eigen::VectorXd& q, Eigen::VectorXd& g) {
    g = polynomial_gradient<double>(q, eps);
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

/// q at the ascending times `at` of q'' + M q = -grad U(q) from (q0, p0), accurate to ~1e-17:
/// classical RK4 in long double (64-bit mantissa) with steps of ~5e-5 and of half that.
/// `gradient` maps a long-double q to grad U. `accuracy` is the largest difference of the two, 15
/// times the error of the finer one (RK4: error ~ h^4) and far above its round-off (~1e-17).
struct Reference {
  std::vector<Eigen::VectorXd> q;
  double accuracy = 0;
};
using VectorLD = Eigen::Matrix<long double, Eigen::Dynamic, 1>;
template <class Gradient>
Reference long_double_reference(const Eigen::MatrixXd& M_double, Gradient&& gradient,
                                const Eigen::VectorXd& q0, const Eigen::VectorXd& p0,
                                const std::vector<double>& at) {
  const Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic> M = M_double.cast<long double>();
  auto acc = [&](const VectorLD& x) -> VectorLD { return -M * x - gradient(x); };
  auto solve = [&](double step) {
    std::vector<VectorLD> out;
    VectorLD q = q0.cast<long double>(), p = p0.cast<long double>();
    double t = 0;
    for (double tau : at) {
      const long n = std::max(1L, std::lround(std::ceil((tau - t) / step)));
      const long double h = ((long double)tau - t) / n;
      for (long k = 0; k < n; ++k) {
        const VectorLD k1q = p, k1p = acc(q);
        const VectorLD k2q = p + h / 2 * k1p, k2p = acc(q + h / 2 * k1q);
        const VectorLD k3q = p + h / 2 * k2p, k3p = acc(q + h / 2 * k2q);
        const VectorLD k4q = p + h * k3p, k4p = acc(q + h * k3q);
        q += h / 6 * (k1q + 2 * k2q + 2 * k3q + k4q);
        p += h / 6 * (k1p + 2 * k2p + 2 * k3p + k4p);
      }
      out.push_back(q), t = tau;
    }
    return out;
  };
  const std::vector<VectorLD> coarse = solve(5e-5), fine = solve(2.5e-5);
  Reference r;
  for (size_t i = 0; i < at.size(); ++i) {
    r.q.push_back(fine[i].cast<double>());
    r.accuracy = std::max(r.accuracy, double((coarse[i] - fine[i]).norm()));
  }
  return r;
}

/// long_double_reference for polynomial_system(eps).
inline Reference polynomial_reference(const Eigen::Vector3d& q0, const Eigen::Vector3d& p0,
                                      const std::vector<double>& at, double eps = 0.5) {
  return long_double_reference(
      polynomial_system(eps).M.matrix(),
      [eps](const VectorLD& x) -> VectorLD {
        return polynomial_gradient<long double>(Eigen::Matrix<long double, 3, 1>(x), eps);
      },
      q0, p0, at);
}

/// Observed order of convergence: the least-squares slope of log(error) against log(h) over the
/// four (three when they span more than kOrderSpan in error) finest step sizes h = T/n whose
/// error is at least kOrderFloor, for n = 4, 6, 8, 11, 16,
/// 23, ... (ratio sqrt 2) up to kOrderMaxSteps (or `max_steps`). `error_at(n)` runs with n steps.
/// Coarse steps can still be dominated by the next order's term, so the fit takes the finest steps
/// the floor allows: order-6 methods reach 1e-13 at n ~ 30 on polynomial_system, order-2 ones not
/// before n = 16384 (the last step count tried). The floor is 1e4 times the reference's accuracy,
/// and the runs' round-off (compensated summation) does not show in the slopes above it.
inline constexpr double kOrderFloor = 1e-13;
inline constexpr long kOrderMaxSteps = 16384;
inline constexpr double kOrderSpan = 1e3;  // the widest error ratio of the fitted points
struct ObservedOrder {
  std::vector<long> n;  // the step counts of the fit
  std::vector<double> error;
  double slope = 0;
};
inline double fitted_slope(const std::vector<long>& n, const std::vector<double>& error) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double k = double(n.size());
  for (size_t i = 0; i < n.size(); ++i) {
    const double x = -std::log(double(n[i])), y = std::log(error[i]);  // log h - log T
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  return (k * sxy - sx * sy) / (k * sxx - sx * sx);
}
template <class F>
ObservedOrder observed_order(F&& error_at, double floor = kOrderFloor,
                             long max_steps = kOrderMaxSteps) {
  ObservedOrder o;
  for (int k = 0;; ++k) {
    const long n = std::lround(4 * std::pow(2.0, k / 2.0));
    if (n > max_steps) break;
    const double err = error_at(n);
    if (err < floor) break;
    o.n.push_back(n), o.error.push_back(err);
  }
  if (o.n.size() < 4) return o;  // (slope 0: too few step sizes above the floor)
  o.n.erase(o.n.begin(), o.n.end() - 4);
  o.error.erase(o.error.begin(), o.error.end() - 4);
  // Four points span 2^(3r/2) in error at order r: beyond kOrderSpan (order >= 7) the coarsest
  // lies before the asymptotic range and is left out. (OMF8(11F11G) on grid_test's small grid:
  // local slopes 8.5 at T/11..T/16, 8.12 and 7.96 at T/23 and T/32; the 4-point fit gave 8.27.)
  if (o.error.front() > kOrderSpan * o.error.back())
    o.n.erase(o.n.begin()), o.error.erase(o.error.begin());
  o.slope = fitted_slope(o.n, o.error);
  return o;
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

/// A copy of a method with one coefficient nudged: bbar_1 *= 1 + kNudge (breaks symplecticity of
/// the implicit methods) and the first non-zero d_i (d_1 but for correctors) *= 1 + kNudge (the
/// weight the explicit path reads: its kicks stay symplectic, but sum d_i = 1 fails).
inline constexpr double kNudge = 5e-2;
inline const generated::Table* nudged_original = nullptr;
inline void nudged_coefficients(double v, double* b, double* bbar, double* abar) {
  nudged_original->coefficients(v, b, bbar, abar);
  bbar[0] *= 1 + kNudge;
}
/// Valid until the next call (one perturbed method at a time).
inline Method perturbed(const Method& m) {
  static generated::Table copy;
  static std::array<double, kMaxStages> d;
  nudged_original = &m.table();
  copy = m.table();
  copy.coefficients = nudged_coefficients;
  std::copy(m.table().d, m.table().d + m.stages(), d.begin());
  *std::find_if(d.begin(), d.end(), [](double x) { return x != 0; }) *= 1 + kNudge;
  copy.d = d.data();
  return Method(m.id(), &copy);
}

/// The state (q, p) after one step of m with step size h from y = (q, p), the stages iterated to
/// round-off: the map must be smooth at 1e-13 for a finite-difference Jacobian.
inline Eigen::VectorXd one_step_map(const Method& m, const System& s, double h,
                                    const Eigen::VectorXd& y) {
  const Eigen::Index d = y.size() / 2;
  Options o;
  o.tolerance = 1e-16;
  Integrator run(m, s, h, y.head(d), y.tail(d), o);
  run.step();
  Eigen::VectorXd out(2 * d);
  out << run.q(), run.p();
  return out;
}

/// max |J^T Omega J - Omega| for the Jacobian J of one_step_map at y (fourth-order central
/// differences): zero up to round-off and truncation for a symplectic one-step map.
inline double symplecticity_defect(const Method& m, const System& s, double h,
                                   const Eigen::VectorXd& y) {
  const Eigen::Index d = y.size() / 2;
  const double e = 1e-3;
  Eigen::MatrixXd J(2 * d, 2 * d);
  for (Eigen::Index j = 0; j < 2 * d; ++j) {
    auto at = [&](double k) {
      Eigen::VectorXd z = y;
      z[j] += k * e;
      return one_step_map(m, s, h, z);
    };
    J.col(j) = (8 * (at(1) - at(-1)) - (at(2) - at(-2))) / (12 * e);
  }
  Eigen::MatrixXd Omega = Eigen::MatrixXd::Zero(2 * d, 2 * d);
  Omega.topRightCorner(d, d).setIdentity();
  Omega.bottomLeftCorner(d, d) = -Eigen::MatrixXd::Identity(d, d);
  return (J.transpose() * Omega * J - Omega).cwiseAbs().maxCoeff();
}

/// d entries uniform in [-1, 1] from a fixed seed.
inline Eigen::VectorXd random_vector(Eigen::Index d, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::VectorXd x(d);
  for (Eigen::Index i = 0; i < d; ++i) x[i] = u(gen);
  return x;
}

}  // namespace erkn::test
