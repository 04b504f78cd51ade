#include "polish.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>

#include "certify.hpp"
#include "trees.hpp"

namespace erkn::gen {
namespace {

// A correction or residual above this is not rounding of the printed digits.
constexpr double kTranscription = 1e-8;

double max_abs(const std::vector<Qs>& r) {
  double m = 0;
  for (const Qs& x : r) m = std::max(m, std::abs(x.to_double()));
  return m;
}

// The free parameters of (c, d, e): all of them, or with the symmetry the first half (and the
// middle weights), c_mid = 1/2. e is empty for plain kicks.
struct Parametrization {
  int s = 0;
  bool symmetric = false;
  bool modified = false;
  int nc() const { return symmetric ? s / 2 : s; }
  int nd() const { return symmetric ? (s + 1) / 2 : s; }
  std::vector<Qs> get(const std::vector<Qs>& c, const std::vector<Qs>& d,
                      const std::vector<Qs>& e) const {
    std::vector<Qs> x(c.begin(), c.begin() + nc());
    x.insert(x.end(), d.begin(), d.begin() + nd());
    if (modified) x.insert(x.end(), e.begin(), e.begin() + nd());
    return x;
  }
  void set(const std::vector<Qs>& x, std::vector<Qs>& c, std::vector<Qs>& d,
           std::vector<Qs>& e) const {
    for (int i = 0; i < s; ++i) {
      const int m = s - 1 - i, k = symmetric ? std::min(i, m) : i;
      if (!symmetric || i != m) c[i] = symmetric && i > m ? Qs(1) - x[k] : x[k];
      if (symmetric && i == m) c[i] = Qs(GiNaC::numeric(1, 2));
      d[i] = x[nc() + k];
      if (modified) e[i] = x[nc() + nd() + k];
    }
  }
};

bool is_symmetric(const std::vector<Qs>& c, const std::vector<Qs>& d, const std::vector<Qs>& e) {
  const int s = int(c.size());
  for (int i = 0; i < s; ++i)
    if (std::abs((c[i] + c[s - 1 - i] - Qs(1)).to_double()) > 1e-12 ||
        std::abs((d[i] - d[s - 1 - i]).to_double()) > 1e-12 ||
        (!e.empty() && std::abs((e[i] - e[s - 1 - i]).to_double()) > 1e-12))
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
  if (unmet > 0) os << "; " << unmet << " conditions of the claim left out (not met)";
  return os.str();
}

namespace {

// Minimum-norm Newton from (c, d, e) onto `conditions`; fills out.c, out.d, out.e, residuals,
// correction.
Polished newton(const std::vector<Qs>& c0, const std::vector<Qs>& d0, const std::vector<Qs>& e0,
                const std::vector<SenTree>& trees, const std::vector<OrderCondition>& conditions,
                int terms) {
  auto R = [&](const std::vector<Qs>& cc, const std::vector<Qs>& dd, const std::vector<Qs>& ee) {
    return residuals(explicit_series(cc, dd, terms, ee), trees, conditions);
  };
  Polished out;
  out.conditions = int(conditions.size());
  Parametrization P{int(c0.size()), is_symmetric(c0, d0, e0), !e0.empty()};
  out.symmetric = P.symmetric;
  std::vector<Qs> c = c0, d = d0, e = e0;
  std::vector<Qs> x = P.get(c, d, e);
  // A parameter given exactly (a drift 0 puts a kick at c = 0: the kick is shared with the next
  // step) is part of the method's structure and stays as given.
  std::vector<bool> fixed;
  for (const Qs& xk : x) fixed.push_back(!xk.is_approx());
  P.set(x, c, d, e);  // symmetrised start
  std::vector<Qs> r = R(c, d, e);
  out.residual_before = max_abs(r);
  const Qs step = Qs::approximate(GiNaC::numeric(1) / GiNaC::numeric(10).power(25));
  const Qs mu = Qs::approximate(GiNaC::numeric(1) / GiNaC::numeric(10).power(40));
  for (int iter = 0; iter < 8 && max_abs(r) > 1e-50; ++iter) {
    // J by central differences (error ~1e-50 in 77-digit arithmetic), then the
    // Levenberg-Marquardt step with mu -> 0: the minimum-norm Newton step.
    const size_t n = x.size(), m = r.size();
    std::vector<std::vector<Qs>> J(m, std::vector<Qs>(n));
    for (size_t k = 0; k < n; ++k) {
      if (fixed[k]) {  // a zero column: the minimum-norm step leaves x[k] alone
        for (size_t i = 0; i < m; ++i) J[i][k] = Qs(0);
        continue;
      }
      std::vector<Qs> xp = x, xm = x, cp = c, dp = d, ep = e, cm = c, dm = d, em = e;
      xp[k] = xp[k] + step, xm[k] = xm[k] - step;
      P.set(xp, cp, dp, ep), P.set(xm, cm, dm, em);
      std::vector<Qs> rp = R(cp, dp, ep), rm = R(cm, dm, em);
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
    for (size_t k = 0; k < n; ++k)
      if (!fixed[k]) x[k] = x[k] + dx[k];  // a fixed parameter stays exact
    P.set(x, c, d, e);
    r = R(c, d, e);
  }
  out.residual_after = max_abs(r);
  for (size_t i = 0; i < c.size(); ++i)
    out.correction = std::max({out.correction, std::abs((c[i] - c0[i]).to_double()),
                               std::abs((d[i] - d0[i]).to_double()),
                               e.empty() ? 0.0 : std::abs((e[i] - e0[i]).to_double())});
  out.c = c, out.d = d, out.e = e;
  return out;
}

// Why a polishing is not acceptable, or "".
std::string failure(const Polished& p) {
  std::ostringstream why;
  if (p.correction > kTranscription)
    why << "the decimals are " << p.correction
        << " away from a method of the claimed order: a transcription error, not rounding";
  else if (p.residual_after > 1e-50)
    why << "Newton left a residual " << p.residual_after;
  return why.str();
}

// The conditions of the orders the decimals meet: with u_K the lowest power of a condition of
// the trees with K f-vertices that they miss by more than kTranscription, and p = min_K u_K - 1
// (the classical order they meet), those of power <= p, and for a claimed generalized order g_K
// those of the K-trees of power <= g_K below u_K.
std::vector<OrderCondition> met_orders(const std::vector<Qs>& c, const std::vector<Qs>& d,
                                       const std::vector<Qs>& e, const std::vector<SenTree>& trees,
                                       const std::vector<OrderCondition>& conditions, int terms,
                                       int order, const std::vector<int>& generalized) {
  const std::vector<Qs> r = residuals(explicit_series(c, d, terms, e), trees, conditions);
  std::map<int, int> lowest_unmet;  // K -> u_K
  int p = order;
  for (size_t i = 0; i < r.size(); ++i)
    if (std::abs(r[i].to_double()) > kTranscription) {
      const int K = trees[conditions[i].tree].fvertices;
      auto [it, fresh] = lowest_unmet.emplace(K, conditions[i].power);
      if (!fresh) it->second = std::min(it->second, conditions[i].power);
      p = std::min(p, conditions[i].power - 1);
    }
  std::vector<OrderCondition> met;
  for (const OrderCondition& oc : conditions) {
    const int K = trees[oc.tree].fvertices;
    const auto u = lowest_unmet.find(K);
    const int gK = K <= int(generalized.size()) ? generalized[K - 1] : 0;
    if (oc.power <= p || (oc.power <= gK && (u == lowest_unmet.end() || oc.power < u->second)))
      met.push_back(oc);
  }
  return met;
}

}  // namespace

Polished polish_explicit(const std::string& method, std::vector<Qs> c, std::vector<Qs> d,
                         std::vector<Qs> e, int order, const std::vector<int>& generalized) {
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
  Polished out = newton(c, d, e, trees, conditions, terms);
  const std::string why = failure(out);
  if (why.empty()) return out;
  // The claim is not what the decimals satisfy (a wrong order, or a transcription error): polish
  // onto the orders they do meet to kTranscription, and leave the refusal to the certification,
  // which names the first failing tree and its residual. Whole orders, not single conditions:
  // a condition of a higher order that happens to be small is not one the method satisfies.
  std::vector<OrderCondition> met =
      met_orders(c, d, e, trees, conditions, terms, order, generalized);
  if (met.size() < conditions.size()) {
    Polished partial = newton(c, d, e, trees, met, terms);
    partial.unmet = int(conditions.size() - met.size());
    if (failure(partial).empty()) return partial;
  }
  throw std::runtime_error(method + ": polishing failed: " + why);
}

}  // namespace erkn::gen
