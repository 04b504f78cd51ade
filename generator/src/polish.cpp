#include "polish.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "certify.hpp"
#include "trees.hpp"

namespace erkn::gen {
namespace {

double max_abs(const std::vector<Qs>& r) {
  double m = 0;
  for (const Qs& x : r) m = std::max(m, std::abs(x.to_double()));
  return m;
}

// The free parameters of (c, d): all of them, or with the symmetry the first half (and the middle
// weight), c_mid = 1/2.
struct Parametrization {
  int s = 0;
  bool symmetric = false;
  std::vector<Qs> get(const std::vector<Qs>& c, const std::vector<Qs>& d) const {
    std::vector<Qs> x;
    for (int i = 0; i < (symmetric ? s / 2 : s); ++i) x.push_back(c[i]);
    for (int i = 0; i < (symmetric ? (s + 1) / 2 : s); ++i) x.push_back(d[i]);
    return x;
  }
  void set(const std::vector<Qs>& x, std::vector<Qs>& c, std::vector<Qs>& d) const {
    const int nc = symmetric ? s / 2 : s;
    for (int i = 0; i < s; ++i) {
      const int m = s - 1 - i;
      if (!symmetric) {
        c[i] = x[i], d[i] = x[s + i];
        continue;
      }
      const int k = std::min(i, m);
      c[i] = i == m ? Qs(GiNaC::numeric(1, 2)) : (i < m ? x[k] : Qs(1) - x[k]);
      d[i] = x[nc + k];
    }
  }
};

bool is_symmetric(const std::vector<Qs>& c, const std::vector<Qs>& d) {
  const int s = int(c.size());
  for (int i = 0; i < s; ++i)
    if (std::abs((c[i] + c[s - 1 - i] - Qs(1)).to_double()) > 1e-12 ||
        std::abs((d[i] - d[s - 1 - i]).to_double()) > 1e-12)
      return false;
  return true;
}

// Solves (A + mu I) x = b by Gaussian elimination with partial pivoting (A symmetric, n x n).
std::vector<Qs> solve(std::vector<std::vector<Qs>> A, std::vector<Qs> b) {
  const size_t n = b.size();
  for (size_t k = 0; k < n; ++k) {
    size_t p = k;
    for (size_t i = k + 1; i < n; ++i)
      if (std::abs(A[i][k].to_double()) > std::abs(A[p][k].to_double())) p = i;
    std::swap(A[k], A[p]), std::swap(b[k], b[p]);
    Qs inv = A[k][k].inverse();
    for (size_t i = k + 1; i < n; ++i) {
      Qs f = A[i][k] * inv;
      for (size_t j = k; j < n; ++j) A[i][j] = A[i][j] - f * A[k][j];
      b[i] = b[i] - f * b[k];
    }
  }
  std::vector<Qs> x(n);
  for (size_t k = n; k-- > 0;) {
    Qs sum = b[k];
    for (size_t j = k + 1; j < n; ++j) sum = sum - A[k][j] * x[j];
    x[k] = sum * A[k][k].inverse();
  }
  return x;
}

}  // namespace

std::string Polished::summary() const {
  std::ostringstream os;
  os.precision(2);
  os << "decimals polished by a minimum-norm Newton correction onto the " << conditions
     << " order conditions they must satisfy" << (symmetric ? " (symmetry kept)" : "")
     << ": largest change " << correction << ", largest residual " << residual_before << " -> "
     << residual_after;
  return os.str();
}

Polished polish_explicit(const std::string& method, std::vector<Qs> c, std::vector<Qs> d, int order,
                         const std::vector<int>& generalized) {
  const int max_power = std::max(
      order, generalized.empty() ? 0 : *std::max_element(generalized.begin(), generalized.end()));
  const auto trees = sen_trees(max_power);
  std::vector<OrderCondition> conditions;
  for (const OrderCondition& oc : order_conditions(trees, max_power)) {
    const int K = trees[oc.tree].fvertices;
    if (oc.power <= order || (K <= int(generalized.size()) && oc.power <= generalized[K - 1]))
      conditions.push_back(oc);
  }
  const int terms = max_power / 2 + 1;
  auto R = [&](const std::vector<Qs>& cc, const std::vector<Qs>& dd) {
    return residuals(explicit_series(cc, dd, terms), trees, conditions);
  };
  Polished out;
  out.conditions = int(conditions.size());
  Parametrization P{int(c.size()), is_symmetric(c, d)};
  out.symmetric = P.symmetric;
  const std::vector<Qs> c0 = c, d0 = d;
  std::vector<Qs> x = P.get(c, d);
  P.set(x, c, d);  // symmetrised start
  std::vector<Qs> r = R(c, d);
  out.residual_before = max_abs(r);
  const Qs step = Qs::approximate(GiNaC::numeric(1) / GiNaC::numeric(10).power(25));
  const Qs mu = Qs::approximate(GiNaC::numeric(1) / GiNaC::numeric(10).power(40));
  for (int iter = 0; iter < 8 && max_abs(r) > 1e-50; ++iter) {
    // J by central differences (error ~1e-50 in 77-digit arithmetic), then the
    // Levenberg-Marquardt step with mu -> 0: the minimum-norm Newton step.
    const size_t n = x.size(), m = r.size();
    std::vector<std::vector<Qs>> J(m, std::vector<Qs>(n));
    for (size_t k = 0; k < n; ++k) {
      std::vector<Qs> xp = x, xm = x, cp = c, dp = d, cm = c, dm = d;
      xp[k] = xp[k] + step, xm[k] = xm[k] - step;
      P.set(xp, cp, dp), P.set(xm, cm, dm);
      std::vector<Qs> rp = R(cp, dp), rm = R(cm, dm);
      for (size_t i = 0; i < m; ++i) J[i][k] = (rp[i] - rm[i]) * (step + step).inverse();
    }
    std::vector<std::vector<Qs>> A(n, std::vector<Qs>(n, Qs(0)));
    std::vector<Qs> g(n, Qs(0));
    for (size_t i = 0; i < m; ++i)
      for (size_t k = 0; k < n; ++k) {
        g[k] = g[k] - J[i][k] * r[i];
        for (size_t l = 0; l < n; ++l) A[k][l] = A[k][l] + J[i][k] * J[i][l];
      }
    for (size_t k = 0; k < n; ++k) A[k][k] = A[k][k] + mu;
    std::vector<Qs> dx = solve(A, g);
    for (size_t k = 0; k < n; ++k) x[k] = x[k] + dx[k];
    P.set(x, c, d);
    r = R(c, d);
  }
  out.residual_after = max_abs(r);
  for (size_t i = 0; i < c.size(); ++i)
    out.correction = std::max({out.correction, std::abs((c[i] - c0[i]).to_double()),
                               std::abs((d[i] - d0[i]).to_double())});
  std::ostringstream why;
  if (out.correction > 1e-8)
    why << "the decimals are " << out.correction
        << " away from a method of the claimed order: a transcription error, not rounding";
  else if (out.residual_after > 1e-50)
    why << "Newton left a residual " << out.residual_after;
  if (!why.str().empty()) throw std::runtime_error(method + ": polishing failed: " + why.str());
  out.c = c, out.d = d;
  return out;
}

}  // namespace erkn::gen
