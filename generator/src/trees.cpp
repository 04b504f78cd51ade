#include "trees.hpp"

#include <functional>
#include <sstream>

using GiNaC::numeric;

namespace erkn::gen {
namespace {

numeric factorial(int n) { return GiNaC::factorial(numeric(n)); }

// A child of an f-vertex: a p-leaf (tree < 0) or the subtree `tree` reached through M^k.
struct ChildType {
  int k = 0, tree = -1, size = 1;
};

std::string child_name(const ChildType& t, const std::vector<SenTree>& trees) {
  if (t.tree < 0) return "p";
  std::string m = t.k == 0 ? "" : (t.k == 1 ? "M " : "M^" + std::to_string(t.k) + " ");
  return m + trees[t.tree].name;
}

SenTree make_tree(const std::vector<int>& children, const std::vector<ChildType>& types,
                  const std::vector<SenTree>& trees) {
  SenTree t;
  t.kappa = 1;
  std::string inner;
  for (int id : children) {
    const ChildType& c = types[id];
    t.size += c.size;
    inner += (inner.empty() ? "" : ",") + child_name(c, trees);
    if (c.tree < 0) {
      ++t.p_leaves;
      continue;
    }
    const SenTree& sub = trees[c.tree];
    t.f_children.emplace_back(c.k, c.tree);
    t.fvertices += sub.fvertices;
    t.nystrom = t.nystrom && sub.nystrom && c.k == 0;
    // int_0^z (-1)^k (z - s)^(2k+1)/(2k+1)! * kappa s^m ds = kappa (-1)^k m!/(2k+m+2)! z^(2k+m+2)
    numeric sign = c.k % 2 ? -1 : 1;
    t.kappa *= sub.kappa * sign * factorial(sub.size) / factorial(2 * c.k + sub.size + 2);
  }
  t.name = inner.empty() ? "f" : "f[" + inner + "]";
  return t;
}

}  // namespace

numeric SenTree::rho_factorial_over_gamma() const { return kappa * factorial(size); }

std::vector<SenTree> sen_trees(int max_rho) {
  std::vector<SenTree> trees;
  std::vector<ChildType> types{ChildType{}};
  std::vector<int> first_of_size;  // index of the first tree of each size
  for (int n = 0; n < max_rho; ++n) {
    // Child types of size n: M^k applied to a tree of size n - 2 - 2k.
    for (int k = 0; 2 + 2 * k <= n; ++k)
      for (size_t t = 0; t < trees.size(); ++t)
        if (trees[t].size == n - 2 - 2 * k) types.push_back({k, int(t), n});
    // Trees of size n: multisets (non-decreasing type ids) of child types summing to n.
    std::vector<int> chosen;
    std::vector<SenTree> fresh;
    std::function<void(size_t, int)> choose = [&](size_t from, int rest) {
      if (rest == 0) {
        fresh.push_back(make_tree(chosen, types, trees));
        return;
      }
      for (size_t id = from; id < types.size(); ++id)
        if (types[id].size <= rest) {
          chosen.push_back(int(id));
          choose(id, rest - types[id].size);
          chosen.pop_back();
        }
    };
    choose(0, n);
    trees.insert(trees.end(), fresh.begin(), fresh.end());
  }
  return trees;
}

std::vector<OrderCondition> order_conditions(const std::vector<SenTree>& trees, int max_power) {
  std::vector<OrderCondition> out;
  for (int power = 1; power <= max_power; ++power)
    for (size_t t = 0; t < trees.size(); ++t)
      for (bool bbar : {false, true}) {
        const int rho = trees[t].rho(), twice_j = power - rho - (bbar ? 1 : 0);
        if (twice_j < 0 || twice_j % 2) continue;
        const int j = twice_j / 2;
        // [V^j] phi_m(V) = (-1)^j/(2j + m)!, m = rho + 1 (bbar) or rho (b)
        numeric sign = j % 2 ? -1 : 1;
        const int m = rho + (bbar ? 1 : 0);
        numeric rhs = trees[t].rho_factorial_over_gamma() * sign / factorial(2 * j + m);
        out.push_back({int(t), bbar, j, power, rhs});
      }
  return out;
}

std::string OrderCondition::text(const std::vector<SenTree>& trees) const {
  const SenTree& t = trees[tree];
  std::string m = std::to_string(t.rho() + (bbar ? 1 : 0));
  std::string lhs = std::string(bbar ? "bbar" : "b") + "^T Phi(" + t.name + ")";
  std::ostringstream os;
  os << "[V^" << j << "] " << lhs << " = " << t.rho_factorial_over_gamma() << " [V^" << j << "] phi"
     << m << "(V) = " << rhs;
  return os.str();
}

}  // namespace erkn::gen
