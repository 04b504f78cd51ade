#include "numerics.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

using GiNaC::numeric;

namespace erkn::gen {
namespace {

constexpr int kDigits = 50;

// Bisection for a sign change of f on [lo, hi] in kDigits digits.
template <class F>
numeric bisect(F f, numeric lo, numeric hi) {
  numeric flo = f(lo);
  numeric eps = numeric(10).power(-kDigits + 10);
  while (hi - lo > eps * hi) {
    numeric mid = (lo + hi) / 2, fm = f(mid);
    if ((fm.csgn() < 0) == (flo.csgn() < 0))
      lo = mid, flo = fm;
    else
      hi = mid;
  }
  return (lo + hi) / 2;
}

double max_omega(const TrigPoly& p) {
  double w = 1;
  for (const auto& [k, c] : p.terms()) w = std::max(w, k.omega.to_double());
  return w;
}

}  // namespace

std::vector<double> real_poles(const Rational& r0, double vmax) {
  Rational r = r0.cleared();
  if (r.is_poly()) return {};
  const TrigEval D(r.den, kDigits), dD(r.den.derivative(), kDigits), N(r.num, kDigits);
  long saved = GiNaC::Digits;
  GiNaC::Digits = kDigits;
  double xmax = std::sqrt(vmax), step = std::min(2e-3, 0.05 / max_omega(r.den));
  std::vector<numeric> roots;
  double x0 = step, f0 = D(x0), g0 = dD(x0);
  for (double x1 = 2 * step; x1 <= xmax + step; x1 += step) {
    double f1 = D(x1), g1 = dD(x1);
    if ((f0 < 0) != (f1 < 0)) {
      roots.push_back(bisect(D, numeric(x0), numeric(x1)));
    } else if ((g0 < 0) != (g1 < 0)) {  // an extremum: a double zero if den vanishes there
      numeric xe = bisect(dD, numeric(x0), numeric(x1));
      if (GiNaC::abs(D(xe)) <= numeric(1e-30) * numeric(D.magnitude(xe.to_double())))
        roots.push_back(xe);
    }
    x0 = x1, f0 = f1, g0 = g1;
  }
  std::vector<double> poles;
  for (const numeric& x : roots) {
    double v = (x * x).to_double();
    if (v <= 0 || v > vmax) continue;
    if (GiNaC::abs(N(x)) <= numeric(1e-30) * numeric(N.magnitude(x.to_double()))) {
      GiNaC::Digits = saved;
      throw std::runtime_error("removable singularity (0/0) at v = " + std::to_string(v));
    }
    poles.push_back(v);
  }
  GiNaC::Digits = saved;
  return poles;
}

double series_switch(const Rational& r0, const std::vector<double>& series) {
  Rational r = r0.cleared();
  if (r.den.is_constant()) return 0;
  const double eps_budget = 32;  // at most 5 bits lost to cancellation
  auto horner_tail_ok = [&](double v) {
    double value = 0, tail = 0;
    for (int k = int(series.size()) - 1; k >= 0; --k) value = value * v + series[k];
    tail = std::abs(series.back()) * std::pow(v, series.size() - 1);
    return tail <= 1e-17 * std::max(1.0, std::abs(value));
  };
  const TrigEval N(r.num, 20), D(r.den, 20);
  // Rounding each term of num and den costs eps * magnitude; the quotient q = num/den then errs
  // by about eps * (|num|_m + |q| |den|_m) / |den|, to compare with eps * max(1, |q|).
  auto closed_ok = [&](double v) {
    double x = std::sqrt(v);
    double q = N(x) / D(x);
    double err = (N.magnitude(x) + std::abs(q) * D.magnitude(x)) / std::abs(D(x));
    return err <= eps_budget * std::max(1.0, std::abs(q));
  };
  for (int e = -10; e <= 6; ++e) {
    double vs = std::ldexp(1.0, e);
    if (!horner_tail_ok(vs)) break;
    if (closed_ok(vs) && closed_ok(1.5 * vs) && closed_ok(2 * vs)) return vs;
  }
  throw std::runtime_error("no v where both the series and the closed form are accurate");
}

void locate_poles(Coefficient& k) {
  std::vector<double> series;
  for (const Qs& q : k.series) series.push_back(q.to_double());
  k.poles = real_poles(k.closed_form, kPoleSearchMax);
  k.series_switch = series_switch(k.closed_form, series);
}

}  // namespace erkn::gen
