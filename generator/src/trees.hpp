// SEN-trees of the ERKN order theory (Wu, You, Shi & Wang 2010; the paper's Theorem 1, eq. (f))
// and the order conditions they index.
//
// Expanding f(Q_i) and f(q(t_n + z h)) (f = -grad U) around q_n gives elementary differentials
// built from f-vertices. A vertex's children are p-leaves (the argument p_n, weight c_i resp.
// z) or f-subtrees reached through M^k: the V^k Taylor coefficient abar_ij^(k) of the stage
// coefficients, resp. of the exact kernel (z - s) phi1((z - s)^2 V). The k are the M-vertices
// that extend Nystrom trees; leaves M^k q_n and M^k p_n of the linear part carry the same
// weights c^2k and c^(2k+1) in the method and in the exact flow, so they only repeat the
// conditions of trees with 2k resp. 2k+1 p-leaves and are not listed.
// A tree tau has |tau| = its power of h in f(Q_i) (p-leaf 1, f-child through M^k 2 + 2k + its
// own size) and rho(tau) = |tau| + 1. Its exact weight is kappa(tau) z^|tau|, and comparing
// h^2 bbar^T(V) f(Q) and h b^T(V) f(Q) with the variation-of-constants formula gives eq. (f):
//   bbar^T(V) Phi(tau) = rho!/gamma phi_{rho+1}(V),  b^T(V) Phi(tau) = rho!/gamma phi_rho(V),
// rho!/gamma = kappa (rho - 1)!, one condition per power V^j of the root (M^j applied to the
// elementary differential), of total power h^(rho+1+2j) resp. h^(rho+2j).
#pragma once

#include <ginac/ginac.h>

#include <string>
#include <utility>
#include <vector>

namespace erkn::gen {

struct SenTree {
  int p_leaves = 0;
  /// f-children as (k, index of the subtree): reached through abar^(k), i.e. M^k.
  std::vector<std::pair<int, int>> f_children;
  int size = 0;          ///< |tau|: its power of h in f(Q_i)
  int fvertices = 1;     ///< number of f-vertices: for H = A + eps B it carries eps^fvertices
  bool nystrom = true;   ///< no M-vertex (k = 0 throughout): a classical Nystrom tree
  GiNaC::numeric kappa;  ///< exact elementary weight kappa * z^size
  std::string name;      ///< e.g. "f[p,M f[p]]"
  int rho() const { return size + 1; }
  GiNaC::numeric rho_factorial_over_gamma() const;  ///< kappa (rho-1)!
};

/// Every SEN-tree with rho <= max_rho, by increasing rho; subtrees precede their parents.
std::vector<SenTree> sen_trees(int max_rho);

/// One condition of eq. (f): [V^j] of bbar^T(V) Phi(tau) (bbar) or b^T(V) Phi(tau) equals rhs.
struct OrderCondition {
  int tree = 0;
  bool bbar = false;
  int j = 0;
  int power = 0;  ///< the power of h it controls: rho + 2j (b) or rho + 1 + 2j (bbar)
  GiNaC::numeric rhs;
  std::string text(const std::vector<SenTree>& trees) const;
};

/// Every condition of power <= max_power, by increasing power (then tree, b before bbar).
std::vector<OrderCondition> order_conditions(const std::vector<SenTree>& trees, int max_power);

}  // namespace erkn::gen
