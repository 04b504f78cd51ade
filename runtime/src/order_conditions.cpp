#include "order_conditions.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace erkn::detail {
namespace {

// A special Nystrom tree: a fat root (a force) whose children are meagre vertices, each a leaf
// (weight c_i) or carrying one fat subtree u (weight sum_j abar_ij Phi_j(u)).
struct Tree {
  std::vector<int> children;  // -1: meagre leaf; else index of the fat subtree
  int order = 1;              // rho: all vertices
  int forces = 1;             // fat vertices
  long double gamma = 1;      // density
  std::string name;           // [c, c, [c]]: c a meagre leaf, [...] a meagre vertex over a subtree
};

int child_order(const std::vector<Tree>& t, int k) { return k < 0 ? 1 : 1 + t[k].order; }

Tree make_tree(const std::vector<Tree>& t, const std::vector<int>& children) {
  Tree x;
  x.children = children;
  for (int k : children) {
    x.order += child_order(t, k);
    if (k >= 0) x.forces += t[k].forces, x.gamma *= (1 + t[k].order) * t[k].gamma;
    x.name += (x.name.empty() ? "" : ",") + (k < 0 ? std::string("c") : t[k].name);
  }
  x.gamma *= x.order;
  x.name = "[" + x.name + "]";
  return x;
}

// Every multiset of child types (leaf = -1, then subtrees 0, 1, ...), nondecreasing, of total
// order `left`, appended as trees to `out`.
void children_of(std::vector<Tree>& t, int left, int first, std::vector<int>& partial,
                 std::vector<Tree>& out) {
  if (left == 0) return out.push_back(make_tree(t, partial));
  for (int k = first; k < int(t.size()); ++k) {
    if (child_order(t, k) > left) continue;
    partial.push_back(k);
    children_of(t, left - child_order(t, k), k, partial, out);
    partial.pop_back();
  }
}

std::vector<Tree> special_nystrom_trees(int max_order) {
  std::vector<Tree> t;
  for (int n = 1; n <= max_order; ++n) {
    std::vector<Tree> fresh;
    std::vector<int> partial;
    children_of(t, n - 1, -1, partial, fresh);
    t.insert(t.end(), fresh.begin(), fresh.end());
  }
  return t;
}

std::string describe(const Tree& x, long double sum, long double residual) {
  char buf[200];
  std::snprintf(buf, sizeof buf,
                " (order %d, %d force%s): sum_i d_i Phi_i = %.21Lg, 1/gamma = 1/%.0Lf, "
                "residual %.3Lg",
                x.order, x.forces, x.forces == 1 ? "" : "s", sum, x.gamma, residual);
  return "tree " + x.name + buf;
}

// The norms of OrderReport::error_constant / generalized_error_constant from each tree's
// residual, once the measured orders are known.
void error_constants(OrderReport& r, const std::vector<Tree>& trees,
                     const std::vector<long double>& residual) {
  const auto norm = [&](int order, int K) {
    if (order >= kMaxTreeOrder) return std::numeric_limits<double>::quiet_NaN();
    long double sum = 0;
    for (size_t n = 0; n < trees.size(); ++n)
      if (trees[n].order == order + 1 && (K == 0 || trees[n].forces == K))
        sum += residual[n] * residual[n];
    return double(std::sqrt(sum));
  };
  r.error_constant = norm(r.order, 0);
  for (size_t K = 0; K < r.generalized.size(); ++K)
    r.generalized_error_constant.push_back(norm(r.generalized[K], int(K) + 1));
}

}  // namespace

OrderReport check_order(std::span<const long double> c, std::span<const long double> d, int order,
                        std::span<const int> generalized, long double tolerance) {
  static const std::vector<Tree> trees = special_nystrom_trees(kMaxTreeOrder);
  const size_t s = c.size();
  std::vector<std::vector<long double>> phi(trees.size()), phi_abs(trees.size());
  OrderReport r{kMaxTreeOrder, std::vector<int>(generalized.size(), kMaxTreeOrder), "", 0, {}};
  std::vector<long double> residuals(trees.size(), 0);
  for (size_t n = 0; n < trees.size(); ++n) {
    const Tree& x = trees[n];
    phi[n].assign(s, 1), phi_abs[n].assign(s, 1);
    for (size_t i = 0; i < s; ++i)
      for (int k : x.children) {
        long double w = 0, w_abs = 0;  // the child's weight at stage i
        if (k < 0) w = c[i], w_abs = std::abs(c[i]);
        for (size_t j = 0; k >= 0 && j < i; ++j)  // abar_ij = d_j (c_i - c_j), j < i
          w += d[j] * (c[i] - c[j]) * phi[k][j],
              w_abs += std::abs(d[j] * (c[i] - c[j])) * phi_abs[k][j];
        phi[n][i] *= w, phi_abs[n][i] *= w_abs;
      }
    long double sum = 0, scale = 1 / x.gamma;
    for (size_t i = 0; i < s; ++i) sum += d[i] * phi[n][i], scale += std::abs(d[i]) * phi_abs[n][i];
    const long double residual = sum - 1 / x.gamma;
    if (std::abs(residual) <= tolerance * scale) continue;
    residuals[n] = residual;
    r.order = std::min(r.order, x.order - 1);
    if (size_t K = size_t(x.forces); K <= r.generalized.size())
      r.generalized[K - 1] = std::min(r.generalized[K - 1], x.order - 1);
    const bool claimed = x.order <= order || (size_t(x.forces) <= generalized.size() &&
                                              x.order <= generalized[x.forces - 1]);
    if (claimed && r.failure.empty()) r.failure = describe(x, sum, residual);
  }
  error_constants(r, trees, residuals);
  return r;
}

}  // namespace erkn::detail
