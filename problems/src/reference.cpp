#include "erkn/problems/reference.hpp"

#include <algorithm>
#include <boost/numeric/odeint/stepper/runge_kutta_fehlberg78.hpp>
#include <cmath>
#include <stdexcept>
#include <type_traits>
#include <vector>

namespace erkn::problems {
namespace {

// RKF7(8) with fixed steps on y = (q, p), y' = (p, -Mq - grad U(q)), in floating type T.
template <class T>
std::vector<T> integrate_rkf78(const Problem& pr, double t_end, long steps) {
  const int d = pr.dim();
  std::vector<T> y(2 * size_t(d));
  for (int i = 0; i < d; ++i) y[i] = pr.q0[i], y[d + i] = pr.p0[i];
  std::vector<T> q(d), f(d);
  Vec qd(d), fd(d);
  auto system = [&](const std::vector<T>& x, std::vector<T>& dxdt, T) {
    for (int i = 0; i < d; ++i) dxdt[i] = x[d + i];
    if constexpr (std::is_same_v<T, long double>) {
      std::copy(x.begin(), x.begin() + d, q.begin());
      pr.force_ld(q, f);
      std::copy(f.begin(), f.end(), dxdt.begin() + d);
    } else {
      std::copy(x.begin(), x.begin() + d, qd.data());
      pr.force(qd, fd);
      std::copy(fd.data(), fd.data() + d, dxdt.begin() + d);
    }
  };
  boost::numeric::odeint::runge_kutta_fehlberg78<std::vector<T>, T> stepper;
  const T h = T(t_end) / T(steps);
  for (long n = 0; n < steps; ++n) stepper.do_step(system, y, T(n) * h, h);
  y.resize(d);
  return y;
}

template <class T>
Reference reference_rkf78(const Problem& pr, double t_end, double tolerance) {
  // Start where the fastest mode is resolved, h * omega_max <= 1, and halve the step.
  const double omega = std::sqrt(pr.M.eigenvalues(pr.dim()).maxCoeff());
  long steps = std::max(64L, long(std::ceil(omega * t_end)));
  std::vector<T> coarse = integrate_rkf78<T>(pr, t_end, steps);
  for (int halvings = 0; halvings < 12; ++halvings) {
    steps *= 2;
    std::vector<T> fine = integrate_rkf78<T>(pr, t_end, steps);
    T diff = 0;
    for (size_t i = 0; i < fine.size(); ++i)
      diff = std::max(diff, T(std::fabs(fine[i] - coarse[i])));
    if (diff <= tolerance) {
      Vec q(pr.dim());
      for (int i = 0; i < pr.dim(); ++i) q[i] = double(fine[i]);
      return {q, double(diff), steps,
              std::string("RKF7(8), fixed step, ") +
                  (std::is_same_v<T, long double> ? "long double, " : "double, ") +
                  std::to_string(steps) + " steps"};
    }
    coarse = std::move(fine);
  }
  throw std::runtime_error("reference for " + pr.key + " did not reach " +
                           std::to_string(tolerance));
}

}  // namespace

Reference reference_solution(const Problem& pr, double t_end, double tolerance,
                             Precision precision) {
  if (pr.exact) return {(*pr.exact)(t_end), 0, 0, "exact solution (Jacobi sn, Boost.Math)"};
  return precision == Precision::long_double ? reference_rkf78<long double>(pr, t_end, tolerance)
                                             : reference_rkf78<double>(pr, t_end, tolerance);
}

}  // namespace erkn::problems
