#include "step_size_check.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "erkn/error.hpp"
#include "format.hpp"

namespace erkn::detail {
namespace {

// Whether no v in [0, vmax] is within a relative `tolerance` of a pole, decided without a look at
// each eigenvalue when vmax lies well below the smallest pole: for tolerance <= 1/2 and vmax <
// P_1 / 4, every pole P has P - v > 3P/4 > tolerance P, with a margin no rounding of pole_within's
// |v - P| <= tolerance P reaches, so the answer is pole_within's. (pole_within per eigenvalue was
// ~160 of the ~7,250 instructions of a construct + 1-step run of SERKN2s3 at P3: callgrind.)
bool below_every_pole(const Method& method, double vmax, double tolerance) {
  return tolerance <= 0.5 && vmax < 0.25 * method.poles().front();
}

}  // namespace

double nearest_safe_step(const Method& method, double h, const Eigen::VectorXd& eigenvalues,
                         double pole_tolerance) {
  // Unsafe h form intervals [sqrt(P(1-tol)/lambda), sqrt(P(1+tol)/lambda)]; merge them (gaps
  // below a relative margin count as overlap) and step just outside the one holding h.
  std::vector<std::pair<double, double>> bad;
  for (double lambda : eigenvalues)
    if (lambda > 0)
      for (double P : method.poles())
        bad.emplace_back(std::sqrt(P * (1 - pole_tolerance) / lambda),
                         std::sqrt(P * (1 + pole_tolerance) / lambda));
  std::sort(bad.begin(), bad.end());
  const double margin = 1e-9;
  std::vector<std::pair<double, double>> merged;
  for (const auto& [a, b] : bad) {
    if (!merged.empty() && a <= merged.back().second * (1 + 2 * margin))
      merged.back().second = std::max(merged.back().second, b);
    else
      merged.emplace_back(a, b);
  }
  double lo = h, hi = h;
  for (const auto& [a, b] : merged)
    if (a <= h && h <= b) lo = a, hi = b;
  const double below = lo * (1 - margin), above = hi * (1 + margin);
  const double vmax = above * above * eigenvalues.maxCoeff();
  if (vmax > generated::kPoleSearchMax || h - below <= above - h) return below;
  return above;
}

void check_step_size(const Method& method, double h, const Eigen::VectorXd& eigenvalues,
                     double pole_tolerance) {
  // (An entire method, RKN or without poles, has no pole to be near and no range to leave: no
  // scan of the eigenvalues, d of them, 2.5 % of a 10-step run on the 256^2 grid.)
  if (method.entire()) return;
  const double lambda_max = eigenvalues.maxCoeff();
  const double vmax = h * h * lambda_max;
  if (vmax > generated::kPoleSearchMax)
    throw Error(std::string(method.name()) + ": h = " + format(h) + " gives h^2*lambda_max = " +
                format(vmax) + " > " + format(generated::kPoleSearchMax) +
                ", beyond the range where the method's poles are known; use h <= " +
                format(std::sqrt(generated::kPoleSearchMax / lambda_max)));
  if (below_every_pole(method, vmax, pole_tolerance)) return;
  for (Eigen::Index k = 0; k < eigenvalues.size(); ++k) {
    const double v = h * h * eigenvalues[k];
    if (const double P = method.pole_within(v, pole_tolerance); P > 0)
      throw Error(std::string(method.name()) + ": step size h = " + format(h, 17) +
                  " puts h^2*lambda = " + format(v, 17) + " (lambda = " + format(eigenvalues[k]) +
                  ", eigenvalue " + std::to_string(k) + " of M) within a relative " +
                  format(pole_tolerance) + " of the pole v = " + format(P, 17) +
                  " of the method's coefficients; nearest safe step size h = " +
                  format(nearest_safe_step(method, h, eigenvalues, pole_tolerance), 17));
  }
}

}  // namespace erkn::detail
