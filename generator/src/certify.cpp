#include "certify.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace erkn::gen {
namespace {

// Phi_i(tau) for every tree: c_i^(p-leaves) times, per f-child (k, sub), sum_j abar_ij^(k) Phi_j.
std::vector<std::vector<Qs>> elementary_weights(const SeriesTableau& t,
                                                const std::vector<SenTree>& trees) {
  std::vector<std::vector<Qs>> phi(trees.size(), std::vector<Qs>(t.s));
  for (size_t n = 0; n < trees.size(); ++n)
    for (int i = 0; i < t.s; ++i) {
      Qs w(1);
      for (int l = 0; l < trees[n].p_leaves; ++l) w = w * t.c[i];
      for (const auto& [k, sub] : trees[n].f_children) {
        Qs sum(0);
        for (int j = 0; j <= i; ++j) sum = sum + t.abar[i * (i + 1) / 2 + j][k] * phi[sub][j];
        w = w * sum;
      }
      phi[n][i] = w;
    }
  return phi;
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
  return approx({t.c}) || approx(t.b) || approx(t.bbar) || approx(t.abar);
}

}  // namespace

std::vector<Qs> residuals(const SeriesTableau& t, const std::vector<SenTree>& trees,
                          const std::vector<OrderCondition>& conditions) {
  const auto phi = elementary_weights(t, trees);
  std::vector<Qs> out;
  for (const OrderCondition& oc : conditions) {
    Qs r = -Qs(oc.rhs);
    for (int i = 0; i < t.s; ++i) r = r + (oc.bbar ? t.bbar : t.b)[i][oc.j] * phi[oc.tree][i];
    out.push_back(r);
  }
  return out;
}

SeriesTableau explicit_series(const std::vector<Qs>& c, const std::vector<Qs>& d, int terms) {
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
  const auto phi = elementary_weights(t, out.trees);
  for (int K = 1; 2 * K - 1 <= max_power; ++K) out.generalized.push_back(max_power);
  for (const OrderCondition& oc : order_conditions(out.trees, max_power)) {
    const SenTree& tree = out.trees[oc.tree];
    if (rkn && (oc.j > 0 || !tree.nystrom)) continue;
    Qs residual = -Qs(oc.rhs);
    for (int i = 0; i < t.s; ++i)
      residual = residual + (oc.bbar ? t.bbar : t.b)[i][oc.j] * phi[oc.tree][i];
    CheckedCondition row{oc, residual.is_approx() ? approx_string(residual) : residual.to_string(),
                         residual.is_zero()};
    if (!row.holds) {
      out.order = std::min(out.order, oc.power - 1);
      int& g = out.generalized[tree.fvertices - 1];
      g = std::min(g, oc.power - 1);
    }
    out.checked.push_back(std::move(row));
  }
  return out;
}

}  // namespace erkn::gen
