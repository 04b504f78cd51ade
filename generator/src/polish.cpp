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
// middle weights), c_mid = 1/2; then a processor's drifts, kicks and modified kicks, all of them.
// e is empty for plain kicks.
struct Parametrization {
  int s = 0;
  bool symmetric = false;
  bool modified = false;
  int nc() const { return symmetric ? s / 2 : s; }
  int nd() const { return symmetric ? (s + 1) / 2 : s; }
  std::vector<Qs> get(const std::vector<Qs>& c, const std::vector<Qs>& d, const std::vector<Qs>& e,
                      const Processor& pre) const {
    std::vector<Qs> x(c.begin(), c.begin() + nc());
    x.insert(x.end(), d.begin(), d.begin() + nd());
    if (modified) x.insert(x.end(), e.begin(), e.begin() + nd());
    for (const auto* list : {&pre.drift, &pre.kick, &pre.modified})
      x.insert(x.end(), list->begin(), list->end());
    return x;
  }
  void set(const std::vector<Qs>& x, std::vector<Qs>& c, std::vector<Qs>& d, std::vector<Qs>& e,
           Processor& pre) const {
    for (int i = 0; i < s; ++i) {
      const int m = s - 1 - i, k = symmetric ? std::min(i, m) : i;
      if (!symmetric || i != m) c[i] = symmetric && i > m ? Qs(1) - x[k] : x[k];
      if (symmetric && i == m) c[i] = Qs(GiNaC::numeric(1, 2));
      d[i] = x[nc() + k];
      if (modified) e[i] = x[nc() + nd() + k];
    }
    size_t next = nc() + nd() + (modified ? nd() : 0);
    for (auto* list : {&pre.drift, &pre.kick, &pre.modified})
      for (Qs& y : *list) y = x[next++];
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

// A method's coefficients: the kernel's (c, d, e) and a processor (empty: none).
struct Point {
  std::vector<Qs> c, d, e;
  Processor pre;
};

// The residuals of `conditions` at x (psi = pi o K o pi^-1 for a processed method).
struct Residuals {
  const std::vector<SenTree>& trees;
  const std::vector<OrderCondition>& conditions;
  int terms;
  std::vector<Qs> operator()(const Point& x) const {
    const KickSequence psi = composition(x.c, x.d, x.e, x.pre);
    return residuals(explicit_series(psi.c, psi.d, terms, psi.e), trees, conditions);
  }
};

// The Jacobian of R at x (parameters P.get) by central differences (error ~1e-50 in 77-digit
// arithmetic); a fixed parameter's column is zero, so the minimum-norm step leaves it alone.
std::vector<std::vector<Qs>> jacobian(const Parametrization& P, const Residuals& R, const Point& at,
                                      const std::vector<Qs>& x, const std::vector<bool>& fixed,
                                      size_t m) {
  const Qs step = Qs::approximate(GiNaC::numeric(1) / GiNaC::numeric(10).power(25));
  std::vector<std::vector<Qs>> J(m, std::vector<Qs>(x.size(), Qs(0)));
  for (size_t k = 0; k < x.size(); ++k) {
    if (fixed[k]) continue;
    std::vector<Qs> xp = x, xm = x;
    Point p = at, q = at;
    xp[k] = xp[k] + step, xm[k] = xm[k] - step;
    P.set(xp, p.c, p.d, p.e, p.pre), P.set(xm, q.c, q.d, q.e, q.pre);
    std::vector<Qs> rp = R(p), rm = R(q);
    for (size_t i = 0; i < m; ++i) J[i][k] = (rp[i] - rm[i]) * (step + step).inverse();
  }
  return J;
}

// The Levenberg-Marquardt step with mu -> 0 (the minimum-norm Newton step) for J dx = -r.
std::vector<Qs> newton_step(const std::vector<std::vector<Qs>>& J, const std::vector<Qs>& r) {
  const Qs mu = Qs::approximate(GiNaC::numeric(1) / GiNaC::numeric(10).power(40));
  const size_t n = J.empty() ? 0 : J[0].size();
  std::vector<std::vector<Qs>> A(n, std::vector<Qs>(n, Qs(0)));
  std::vector<Qs> g(n, Qs(0));
  for (size_t i = 0; i < r.size(); ++i)
    for (size_t k = 0; k < n; ++k) {
      g[k] = g[k] - J[i][k] * r[i];
      for (size_t l = 0; l < n; ++l) A[k][l] = A[k][l] + J[i][k] * J[i][l];
    }
  for (size_t k = 0; k < n; ++k) A[k][k] = A[k][k] + mu;
  return solve(A, g);
}

double largest_change(const Point& a, const Point& b) {
  double out = 0;
  auto over = [&](const std::vector<Qs>& x, const std::vector<Qs>& y) {
    for (size_t i = 0; i < x.size(); ++i) out = std::max(out, std::abs((x[i] - y[i]).to_double()));
  };
  over(a.c, b.c), over(a.d, b.d), over(a.e, b.e);
  over(a.pre.drift, b.pre.drift), over(a.pre.kick, b.pre.kick);
  over(a.pre.modified, b.pre.modified);
  return out;
}

// Minimum-norm Newton from x0 onto `conditions`; fills out's coefficients, residuals, correction.
Polished newton(const Point& x0, const std::vector<SenTree>& trees,
                const std::vector<OrderCondition>& conditions, int terms) {
  const Residuals R{trees, conditions, terms};
  Polished out;
  out.conditions = int(conditions.size());
  Parametrization P{int(x0.c.size()), is_symmetric(x0.c, x0.d, x0.e), !x0.e.empty()};
  out.symmetric = P.symmetric;
  Point at = x0;
  std::vector<Qs> x = P.get(at.c, at.d, at.e, at.pre);
  // A parameter given exactly (a drift 0 puts a kick at c = 0: the kick is shared with the next
  // step) is part of the method's structure and stays as given.
  std::vector<bool> fixed;
  for (const Qs& xk : x) fixed.push_back(!xk.is_approx());
  P.set(x, at.c, at.d, at.e, at.pre);  // symmetrised start
  std::vector<Qs> r = R(at);
  out.residual_before = max_abs(r);
  for (int iter = 0; iter < 8 && max_abs(r) > 1e-50; ++iter) {
    const std::vector<Qs> dx = newton_step(jacobian(P, R, at, x, fixed, r.size()), r);
    for (size_t k = 0; k < x.size(); ++k)
      if (!fixed[k]) x[k] = x[k] + dx[k];  // a fixed parameter stays exact
    P.set(x, at.c, at.d, at.e, at.pre);
    r = R(at);
  }
  out.residual_after = max_abs(r);
  out.correction = largest_change(at, x0);
  out.c = at.c, out.d = at.d, out.e = at.e, out.pre = at.pre;
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
std::vector<OrderCondition> met_orders(const Point& x, const std::vector<SenTree>& trees,
                                       const std::vector<OrderCondition>& conditions, int terms,
                                       int order, const std::vector<int>& generalized) {
  const std::vector<Qs> r = Residuals{trees, conditions, terms}(x);
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
                         std::vector<Qs> e, int order, const std::vector<int>& generalized,
                         const Processor& pre) {
  const Point x0{std::move(c), std::move(d), std::move(e), pre};
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
  Polished out = newton(x0, trees, conditions, terms);
  const std::string why = failure(out);
  if (why.empty()) return out;
  // The claim is not what the decimals satisfy (a wrong order, or a transcription error): polish
  // onto the orders they do meet to kTranscription, and leave the refusal to the certification,
  // which names the first failing tree and its residual. Whole orders, not single conditions:
  // a condition of a higher order that happens to be small is not one the method satisfies.
  std::vector<OrderCondition> met = met_orders(x0, trees, conditions, terms, order, generalized);
  if (met.size() < conditions.size()) {
    Polished partial = newton(x0, trees, met, terms);
    partial.unmet = int(conditions.size() - met.size());
    if (failure(partial).empty()) return partial;
  }
  throw std::runtime_error(method + ": polishing failed: " + why);
}

}  // namespace erkn::gen
