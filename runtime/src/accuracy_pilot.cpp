#include "accuracy_pilot.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "clock.hpp"
#include "erkn/error.hpp"

namespace erkn::detail {
namespace {

// A pilot estimate this far above the target is refined (not yet asymptotic, and expensive to
// extrapolate from); this far below it, the pilot is made coarser (cheaper, clear of round-off).
constexpr double kAsymptotic = 1e3;

// One attempt with n steps of h over the pilot interval: the step-doubling estimate of the h
// run's error at each checkpoint t_i of the pilot's second half (earlier ones are the size of a
// local error, not yet a trend), grown linearly to the span; the maximum over those t_i.
Pilot attempt(const Method& method, const PilotRequest& r, double h, long n) {
  Pilot out;
  out.h = h;
  const double cpu_0 = cpu_seconds();
  const long every = std::max(1L, n / 8);
  try {
    const Track a = run(method, r, h, n, every), b = run(method, r, h / 2, 2 * n, 2 * every);
    out.gradients = a.gradients + b.gradients;
    const double two_p = std::exp2(order_at(r, h)), richardson = two_p / (two_p - 1);
    double roundoff = 0;
    for (size_t i = 0; i < a.q.size() && i < b.q.size(); ++i) {
      const double e = (a.q[i] - b.q[i]).lpNorm<Eigen::Infinity>() * richardson;
      if (!std::isfinite(e)) throw Error("the pilot's state is not finite");
      if (2 * a.t[i] < a.t.back()) continue;
      out.error = std::max(out.error, e * r.span / a.t[i]);
      roundoff = std::max(roundoff, 64 * std::numeric_limits<double>::epsilon() * double(n) *
                                        a.q[i].lpNorm<Eigen::Infinity>());
    }
    out.at_roundoff = out.error * a.t.back() / r.span <= roundoff;
    out.interval = a.t.back();
    out.ok = true;
  } catch (const Error& e) {  // a step the method refuses or that blows up at this h
    out.failure = e.what();
  }
  out.cpu = cpu_seconds() - cpu_0;
  out.cpu_per_gradient = out.gradients > 0 ? out.cpu / double(out.gradients) : 0;
  return out;
}

}  // namespace

Track run(const Method& method, const PilotRequest& r, double h, long n, long every) {
  Integrator it(method, *r.system, h, *r.q0, *r.p0, r.options);
  Track out;
  it.integrate(
      double(n) * h,
      [&](double t, const Eigen::VectorXd& q, const Eigen::VectorXd&) {
        out.t.push_back(t), out.q.push_back(q);
      },
      every);
  out.gradients = it.statistics().gradient_evaluations;
  return out;
}

Pilot calibrated_pilot(const Method& method, const PilotRequest& request, double h_start,
                       double target) {
  PilotRequest r = request;  // the interval grows when two steps over it are already too fine
  double h = h_start, cpu = 0;
  long gradients = 0;
  Pilot last;
  for (int k = 0; k < 8; ++k) {
    const long n = std::max(2L, std::lround(r.pilot / h));
    h = r.pilot / double(n);
    last = attempt(method, r, h, n);
    cpu += last.cpu, gradients += last.gradients;
    const bool too_fine = last.ok && last.error < target / kAsymptotic;
    if (!last.ok) {
      h /= 4;
    } else if (last.error > kAsymptotic * target) {
      h *= std::clamp(std::pow(100 * target / last.error, 1 / order_at(r, h)), 0.125, 0.5);
    } else if (too_fine && n > 2) {
      h *= std::clamp(std::pow(target / last.error, 1 / order_at(r, h)) / 4, 2.0, 4.0);
    } else if (too_fine && r.pilot < r.span) {
      r.pilot = std::min(r.span, 4 * r.pilot), h *= 4;
    } else {
      break;
    }
  }
  last.cpu = cpu, last.gradients = gradients;
  return last;
}

double order_at(const PilotRequest& r, double h) {
  const double ratio = r.shape(h) / r.shape(h / 2);
  return std::isfinite(ratio) && ratio > 2 ? std::log2(ratio) : 1.0;
}

double step_for(const PilotRequest& r, const Pilot& pilot, double target) {
  if (pilot.error <= 0) return r.span;  // exact (e.g. U = 0): one step
  const double level = r.shape(pilot.h) * target / pilot.error;
  return r.shape.step_at(level, pilot.at_roundoff ? std::min(r.span, 4 * pilot.h) : r.span);
}

// The a priori error model without F (t_end - t0) and r^K: sum_K r^K C_K h^(g_K); the classical
// C h^p where the generalized constants are unknown.
ErrorShape error_shape(const Method& m, double r) {
  const auto g = m.generalized_order();
  const auto C = m.generalized_error_constant();
  ErrorShape out;
  for (size_t K = 0; K < g.size(); ++K)
    if (std::isfinite(C[K]) && C[K] > 0)
      out.c.push_back(std::pow(r, double(K + 1)) * C[K]), out.g.push_back(g[K]);
  if (out.c.empty() && std::isfinite(m.error_constant()) && m.error_constant() > 0)
    out.c.push_back(m.error_constant()), out.g.push_back(m.order());
  return out;
}

Eigen::VectorXd distinct(const Eigen::VectorXd& values) {
  std::vector<double> v(values.data(), values.data() + values.size());
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end(),
                      [](double a, double b) { return b - a <= 1e-12 * std::abs(b); }),
          v.end());
  return Eigen::Map<const Eigen::VectorXd>(v.data(), Eigen::Index(v.size()));
}

double ErrorShape::operator()(double h) const {
  double sum = 0;
  for (size_t k = 0; k < c.size(); ++k) sum += c[k] * std::pow(h, g[k]);
  return sum;
}

double ErrorShape::step_at(double level, double h_max) const {
  // Start at the smallest h where one term alone reaches the level: the sum is >= level there,
  // so Newton (convex in ln h) descends monotonically from it, in a few steps when one term
  // dominates (was from h_max: ~10 steps more, 20-29 % of a choice's CPU on FPU and HH by perf).
  double x = std::log(h_max);
  for (size_t k = 0; k < c.size(); ++k) x = std::min(x, std::log(level / c[k]) / g[k]);
  for (int it = 0; it < 100; ++it) {
    double sum = 0, slope = 0;  // shape and d shape / d ln h at h = e^x
    for (size_t k = 0; k < c.size(); ++k) {
      const double term = c[k] * std::exp(g[k] * x);
      sum += term, slope += g[k] * term;
    }
    if (sum <= level && it == 0) return std::min(h_max, std::exp(x));
    const double dx = (std::log(sum) - std::log(level)) * sum / slope;
    if (!std::isfinite(dx)) break;
    x -= dx;
    if (std::abs(dx) < 1e-10) break;
  }
  return std::min(h_max, std::exp(x));
}

}  // namespace erkn::detail
