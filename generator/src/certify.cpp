#include "certify.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace erkn::gen {
namespace {

// The elementary weights of every tree at every stage: plain[n][i] of f(Q_i) and, with modified
// kicks, mod[n][i] of f'(Q_i) f(Q_i).
struct Weights {
  std::vector<std::vector<Qs>> plain, mod;
};

// Child sum S_i(k, sub) = sum_j abar_ij^(k) Phi_j(sub) + abar_mod_ij^(k) Psi_j(sub): the weight
// of M^k applied to the part of Q_i - (linear flow) that is the tree `sub`.
Qs child_sum(const SeriesTableau& t, const Weights& w, int i, int k, int sub) {
  Qs sum(0);
  for (int j = 0; j <= i; ++j) {
    const int ij = i * (i + 1) / 2 + j;
    sum = sum + t.abar[ij][k] * w.plain[sub][j];
    if (t.modified()) sum = sum + t.abar_mod[ij][k] * w.mod[sub][j];
  }
  return sum;
}

// Phi_i(tau) = c_i^(p-leaves) prod over f-children (k, sub) of S_i(k, sub): the plain weights.
//
// Psi_i(tau), the weight of f'(Q_i) f(Q_i) (a modified kick): it is the derivative at delta = 0
// of the plain weight of f(Q_i + delta h^2 f(Q_i)), since f(Q + delta h^2 f(Q)) - f(Q) =
// delta h^2 f'(Q) f(Q) + O(delta^2). That extra stage adds delta Phi_i(sub) to the k = 0 child
// sums and leaves the others, so by the product rule over tau's children (a list, with repeats)
//   Psi_i(tau) = c_i^(p-leaves) sum over children r with k_r = 0 of Phi_i(sub_r) prod_(r' != r)
//   S_i,
// i.e. the root's child sub_r is f evaluated at the same point Q_i (no sum over stages, and its
// h^2 is the h^2 of the modified term), and every other child is expanded as usual. The trees
// and their exact weights are the same as for plain kicks: only the method's weights change.
Weights elementary_weights(const SeriesTableau& t, const std::vector<SenTree>& trees) {
  Weights w{std::vector<std::vector<Qs>>(trees.size(), std::vector<Qs>(t.s)), {}};
  if (t.modified()) w.mod = w.plain;
  for (size_t n = 0; n < trees.size(); ++n)
    for (int i = 0; i < t.s; ++i) {
      Qs leaves(1);
      for (int l = 0; l < trees[n].p_leaves; ++l) leaves = leaves * t.c[i];
      const auto& children = trees[n].f_children;
      std::vector<Qs> S;
      for (const auto& [k, sub] : children) S.push_back(child_sum(t, w, i, k, sub));
      Qs phi = leaves;
      for (const Qs& x : S) phi = phi * x;
      w.plain[n][i] = phi;
      if (!t.modified()) continue;
      Qs psi(0);
      for (size_t r = 0; r < children.size(); ++r) {
        if (children[r].first != 0) continue;
        Qs term = leaves * w.plain[children[r].second][i];
        for (size_t q = 0; q < children.size(); ++q)
          if (q != r) term = term * S[q];
        psi = psi + term;
      }
      w.mod[n][i] = psi;
    }
  return w;
}

// lhs - rhs of one condition: sum_i b_i^(j) Phi_i(tau) + b_mod_i^(j) Psi_i(tau) - rhs.
Qs residual_of(const SeriesTableau& t, const Weights& w, const OrderCondition& oc) {
  Qs r = -Qs(oc.rhs);
  for (int i = 0; i < t.s; ++i) {
    r = r + (oc.bbar ? t.bbar : t.b)[i][oc.j] * w.plain[oc.tree][i];
    if (t.modified()) r = r + (oc.bbar ? t.bbar_mod : t.b_mod)[i][oc.j] * w.mod[oc.tree][i];
  }
  return r;
}

// An approximate residual with 3 significant digits. Below 1e-50 it is the round-off of the
// 60-digit arithmetic, whose digits depend on the order of evaluation: printed as a bound, so
// that regeneration is byte-identical.
std::string approx_string(const Qs& x) {
  if (std::abs(x.to_double()) < 1e-50) return "< 1e-50";
  std::ostringstream os;
  os.precision(3);
  os << x.to_double();
  return os.str();
}

bool any_approx(const SeriesTableau& t) {
  auto approx = [](const std::vector<std::vector<Qs>>& rows) {
    for (const auto& row : rows)
      for (const Qs& x : row)
        if (x.is_approx()) return true;
    return false;
  };
  return approx({t.c}) || approx(t.b) || approx(t.bbar) || approx(t.abar) || approx(t.b_mod) ||
         approx(t.bbar_mod) || approx(t.abar_mod);
}

// The norms of Certificate::error_constant and generalized_error_constant: residuals of the
// first failing power, over all trees (K = 0) or the trees with K f-vertices.
double leading_norm(const Certificate& cert, int power, int K) {
  if (power > cert.max_power) return std::numeric_limits<double>::quiet_NaN();
  double sum = 0;
  for (const CheckedCondition& c : cert.checked)
    if (c.condition.power == power && (K == 0 || cert.trees[c.condition.tree].fvertices == K))
      sum += c.value * c.value;
  return std::sqrt(sum);
}

void error_constants(Certificate& cert) {
  cert.error_constant = leading_norm(cert, cert.order + 1, 0);
  for (size_t K = 0; K < cert.generalized.size(); ++K)
    cert.generalized_error_constant.push_back(
        leading_norm(cert, cert.generalized[K] + 1, int(K) + 1));
}

}  // namespace

std::vector<Qs> residuals(const SeriesTableau& t, const std::vector<SenTree>& trees,
                          const std::vector<OrderCondition>& conditions) {
  const Weights w = elementary_weights(t, trees);
  std::vector<Qs> out;
  for (const OrderCondition& oc : conditions) out.push_back(residual_of(t, w, oc));
  return out;
}

SeriesTableau explicit_series(const std::vector<Qs>& c, const std::vector<Qs>& d, int terms,
                              const std::vector<Qs>& e) {
  // K w^m sum_j (-1)^j w^(2j) / (2j + m)!: the series of K w^m phi_m(w^2 V), m = 0, 1.
  auto series = [terms](const Qs& K, const Qs& w, int m) {
    std::vector<Qs> out;
    Qs wp = m == 0 ? Qs(1) : w;
    GiNaC::numeric fact = 1;
    for (int j = 0; j < terms; ++j) {
      if (j > 0) fact = fact * (2 * j + m) * (2 * j + m - 1);
      out.push_back(K * wp * Qs((j % 2 ? -1 : 1) / fact));
      wp = wp * w * w;
    }
    return out;
  };
  SeriesTableau t;
  t.s = int(c.size());
  t.c = c;
  for (int i = 0; i < t.s; ++i) {
    t.b.push_back(series(d[i], Qs(1) - c[i], 0));
    t.bbar.push_back(series(d[i], Qs(1) - c[i], 1));
    for (int j = 0; j <= i; ++j) t.abar.push_back(series(j < i ? d[j] : Qs(0), c[i] - c[j], 1));
  }
  if (std::all_of(e.begin(), e.end(), [](const Qs& x) { return x.is_zero(); })) return t;
  for (int i = 0; i < t.s; ++i) {
    const Qs et = e[i] * Qs(modified_kick_weight);
    t.b_mod.push_back(series(et, Qs(1) - c[i], 0));
    t.bbar_mod.push_back(series(et, Qs(1) - c[i], 1));
    for (int j = 0; j <= i; ++j)
      t.abar_mod.push_back(series(j < i ? e[j] * Qs(modified_kick_weight) : Qs(0), c[i] - c[j], 1));
  }
  return t;
}

const CheckedCondition* Certificate::first_failure() const {
  for (const CheckedCondition& c : checked)
    if (!c.holds) return &c;
  return nullptr;
}

Certificate certify(const SeriesTableau& t, bool rkn, int max_power) {
  Certificate out;
  out.max_power = max_power;
  out.order = max_power;
  out.trees = sen_trees(max_power);
  out.arithmetic = any_approx(t) ? std::to_string(Qs::kApproxDigits) +
                                       "-digit CLN arithmetic; a condition holds if "
                                       "|residual| <= 1e-45"
                                 : "exact arithmetic in the number field of the coefficients";
  const Weights w = elementary_weights(t, out.trees);
  for (int K = 1; 2 * K - 1 <= max_power; ++K) out.generalized.push_back(max_power);
  for (const OrderCondition& oc : order_conditions(out.trees, max_power)) {
    const SenTree& tree = out.trees[oc.tree];
    if (rkn && (oc.j > 0 || !tree.nystrom)) continue;
    const Qs residual = residual_of(t, w, oc);
    CheckedCondition row{oc, residual.is_approx() ? approx_string(residual) : residual.to_string(),
                         residual.to_double(), residual.is_zero()};
    if (!row.holds) {
      out.order = std::min(out.order, oc.power - 1);
      int& g = out.generalized[tree.fvertices - 1];
      g = std::min(g, oc.power - 1);
    }
    out.checked.push_back(std::move(row));
  }
  error_constants(out);
  return out;
}

}  // namespace erkn::gen
