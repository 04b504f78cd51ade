// Order certification: evaluates every order condition of eq. (f) (trees.hpp) on a method's
// Taylor coefficients and finds the highest order whose conditions all hold, exactly (numbers
// of Q(sqrt(s))) or in 60-digit CLN arithmetic against a stated bound (approximate Qs).
#pragma once

#include <string>
#include <vector>

#include "qs.hpp"
#include "trees.hpp"

namespace erkn::gen {

/// Taylor coefficients in V of a method's coefficient functions.
struct SeriesTableau {
  int s = 0;
  std::vector<Qs> c;
  std::vector<std::vector<Qs>> b, bbar;  ///< [i][k]: coefficient of V^k
  std::vector<std::vector<Qs>> abar;     ///< [i(i+1)/2 + j][k], j <= i (0-based)
  /// Modified kicks (empty: none). Stage i's force is d_i f(Q_i) + h^2 et_i f'(Q_i) f(Q_i),
  /// f = -grad U; b_mod, bbar_mod, abar_mod are the kernels of b, bbar, abar that multiply
  /// the second term (for an explicit method the same phi-kernels with et_i in place of d_i).
  std::vector<std::vector<Qs>> b_mod, bbar_mod, abar_mod;
  bool modified() const { return !b_mod.empty(); }
};

struct CheckedCondition {
  OrderCondition condition;
  std::string residual;  ///< exact, or its value in the working precision
  double value = 0;      ///< the residual as a double
  bool holds = false;
};

struct Certificate {
  int order = 0;      ///< highest r: every condition of power <= r holds (max_power if all do)
  int max_power = 0;  ///< conditions were checked up to this power of h
  /// generalized[K-1]: the order in h of the eps^K terms for H = A + eps B (trees with K
  /// f-vertices), capped at max_power.
  std::vector<int> generalized;
  /// The leading local error: the 2-norm of the residuals of every condition of power
  /// order + 1 (the coefficients of h^(order+1) M^j F(tau) in the local errors of q and p, V^j
  /// counting as h^(2j), i.e. the h -> 0 constant at fixed M for both families); NaN if
  /// order == max_power (no condition checked fails).
  double error_constant = 0;
  /// generalized_error_constant[K-1]: the same norm over the trees with K f-vertices at power
  /// generalized[K-1] + 1; NaN where generalized[K-1] == max_power.
  std::vector<double> generalized_error_constant;
  std::vector<CheckedCondition> checked;  ///< every condition checked, by increasing power
  std::string arithmetic;                 ///< how the residuals were computed and judged
  std::vector<SenTree> trees;
  /// The first condition that fails (order + 1 == its power), or nullptr.
  const CheckedCondition* first_failure() const;
};

/// The residuals (lhs - rhs) of `conditions` (indices into `trees`) for the tableau t.
std::vector<Qs> residuals(const SeriesTableau& t, const std::vector<SenTree>& trees,
                          const std::vector<OrderCondition>& conditions);

/// The Taylor coefficients (to V^(terms-1)) of the explicit method with nodes c and weights d:
/// b_i = d_i phi0((1-c_i)^2 V), bbar_i = d_i (1-c_i) phi1((1-c_i)^2 V),
/// abar_ij = d_j (c_i-c_j) phi1((c_i-c_j)^2 V) (j < i), abar_ii = 0; with modified-kick
/// coefficients e (empty or all zero: none) the same kernels with -2 e_i in place of d_i
/// (modified_kick_weight) in b_mod, bbar_mod, abar_mod.
SeriesTableau explicit_series(const std::vector<Qs>& c, const std::vector<Qs>& d, int terms,
                              const std::vector<Qs>& e = {});

/// The factor et/e between the coefficient et of f'(Q) f(Q) in a stage's force (the form the
/// tree expansion uses, f = -grad U) and the spec's e in p -= h (d grad U + h^2 e grad(|grad
/// U|^2)): grad(|grad U|^2) = 2 Hess(U) grad U = 2 f' f, so -h^3 e grad(|grad U|^2) = h^3 (-2 e) f'
/// f.
inline constexpr int modified_kick_weight = -2;

/// Every condition of power <= max_power, exactly or, if a coefficient is approximate, in
/// Qs::kApproxDigits digits with |residual| <= Qs::approx_zero() for "holds".
/// rkn: the V -> 0 limit applied to q'' = -Mq + f: only Nystrom trees and V^0 conditions,
/// with the coefficients' constant terms.
Certificate certify(const SeriesTableau& t, bool rkn, int max_power);

}  // namespace erkn::gen
