// The order conditions of an explicit splitting method (nodes c, kick weights d) checked
// numerically, for methods given as data (Method::load). At V = 0 the method is the RKN method
// b_i = d_i, bbar_i = d_i (1 - c_i), abar_ij = d_j (c_i - c_j) (j < i); a splitting method's order
// conditions are those of its Lie words modulo [B,[B,[B,A]]] = 0, the same for A = p^2/2 + q^T M
// q/2 as for A = p^2/2, so they are the RKN conditions over special Nystrom trees (Hairer, Norsett
// & Wanner I, Sec. II.14): sum_i d_i Phi_i(t) = 1/gamma(t) for every tree t with rho(t) <= order
// (the bbar conditions follow, bbar_i = b_i (1 - c_i)). A tree with K fat vertices (forces)
// carries eps^K for H = A + eps B: the generalized order g_K holds when every K-force tree with
// rho <= g_K does.
#pragma once

#include <span>
#include <string>
#include <vector>

namespace erkn::detail {

/// Trees are enumerated up to this order (the generator certifies up to h^10 as well).
inline constexpr int kMaxTreeOrder = 10;

struct OrderReport {
  int order = 0;                 ///< largest r <= kMaxTreeOrder with every condition rho <= r
  std::vector<int> generalized;  ///< [K-1]: largest g with every K-force condition rho <= g
  /// The first failing condition of the claim (empty: the claim holds), e.g.
  /// "tree [c,[c]] (order 4, 2 forces): sum_i d_i Phi_i = 0.041 != 1/gamma = 1/24, residual ..."
  std::string failure;
  /// 2-norm of the residuals of the trees of order `order + 1` (the measured order), and
  /// per K of the K-force trees of order generalized[K-1] + 1; NaN beyond kMaxTreeOrder. Over
  /// these V^0 special Nystrom conditions only: the generator's Table::error_constant also
  /// counts the M^j F(tau) (j > 0) and q-error conditions, so this is a lower bound of it.
  double error_constant = 0;
  std::vector<double> generalized_error_constant;
};

/// Evaluates every condition in long double; one holds when |sum_i d_i Phi_i - 1/gamma| <=
/// tolerance * sum_i |d_i Phi_i| evaluated in absolute values. `order`, `generalized`: the claim.
OrderReport check_order(std::span<const long double> c, std::span<const long double> d, int order,
                        std::span<const int> generalized, long double tolerance);

}  // namespace erkn::detail
