// SEN-trees and the order conditions of eq. (f) (generator/src/trees.hpp).
#include "trees.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <sstream>
#include <string>
#include <tuple>

namespace erkn::gen {
namespace {

int count_rho(const std::vector<SenTree>& trees, int rho, bool nystrom_only) {
  return int(std::count_if(trees.begin(), trees.end(), [&](const SenTree& t) {
    return t.rho() == rho && (!nystrom_only || t.nystrom);
  }));
}

// The trees without M-vertices are the Nystrom trees of q'' = f(q): their numbers per order are
// the numbers of RKN order conditions, 1, 1, 2, 3, 6, 10, 20, 36, 72, 137 (Hairer, Norsett &
// Wanner, Solving ODEs I, Table II.14.3).
TEST(SenTrees, WithoutMVerticesTheyAreTheNystromTrees) {
  const auto trees = sen_trees(10);
  const int rkn[] = {1, 1, 2, 3, 6, 10, 20, 36, 72, 137};
  for (int rho = 1; rho <= 10; ++rho) EXPECT_EQ(count_rho(trees, rho, true), rkn[rho - 1]) << rho;
}

// With M-vertices, f[M f] appears at rho = 5 first; the counts per rho (recorded in the issue).
TEST(SenTrees, CountsPerOrder) {
  const auto trees = sen_trees(10);
  const int all[] = {1, 1, 2, 3, 7, 12, 27, 51, 113, 227};
  for (int rho = 1; rho <= 10; ++rho) EXPECT_EQ(count_rho(trees, rho, false), all[rho - 1]) << rho;
}

// Each tree's children precede it, its size is the sum of its children's, and the names are
// unique (trees are distinct).
TEST(SenTrees, AreWellFormedAndDistinct) {
  const auto trees = sen_trees(9);
  std::set<std::string> names;
  for (size_t n = 0; n < trees.size(); ++n) {
    int size = trees[n].p_leaves;
    for (const auto& [k, sub] : trees[n].f_children) {
      EXPECT_LT(size_t(sub), n);
      size += 2 + 2 * k + trees[sub].size;
    }
    EXPECT_EQ(size, trees[n].size) << trees[n].name;
    EXPECT_TRUE(names.insert(trees[n].name).second) << trees[n].name;
  }
}

// One condition as the paper prints it: root (b or bbar), tree, rho!/gamma, the phi index, and
// the O(h^k) of eq. (f).
using Printed = std::tuple<std::string, std::string, std::string, int, int>;

// Eq. (f) for order r, one line per tree and root as the paper prints it.
std::set<Printed> conditions_of_order(int r) {
  const auto trees = sen_trees(r);
  std::set<Printed> out;
  for (const SenTree& t : trees)
    for (bool bbar : {false, true}) {
      const int rho = t.rho();
      if (rho > (bbar ? r - 1 : r)) continue;
      std::ostringstream k;
      k << t.rho_factorial_over_gamma();
      out.insert({bbar ? "bbar" : "b", t.name, k.str(), rho + (bbar ? 1 : 0),
                  bbar ? r - rho : r + 1 - rho});
    }
  return out;
}

// (i): order 2, one stage. bbar_1 = phi2 + O(h), b_1 = phi1 + O(h^2), c_1 b_1 = phi2 + O(h).
TEST(OrderConditions, PaperInstanceI) {
  std::set<Printed> paper{
      {"bbar", "f", "1", 2, 1}, {"b", "f", "1", 1, 2}, {"b", "f[p]", "1", 2, 1}};
  EXPECT_EQ(conditions_of_order(2), paper);
}

// (r): order 3, two stages: b^T e, b^T c, b^T c^2 = 2 phi3, bbar^T e, bbar^T c, b^T abar(0) e.
TEST(OrderConditions, PaperInstanceR) {
  std::set<Printed> paper{{"b", "f", "1", 1, 3},       {"b", "f[p]", "1", 2, 2},
                          {"b", "f[p,p]", "2", 3, 1},  {"bbar", "f", "1", 2, 2},
                          {"bbar", "f[p]", "1", 3, 1}, {"b", "f[f]", "1", 3, 1}};
  EXPECT_EQ(conditions_of_order(3), paper);
}

// (s) and (Schems100): order 4, two and three stages: the eleven conditions (the 8th of (s) with
// bbar for the printed b, see docs/errata.md): b^T c^k = k! phi_{k+1} (k <= 3), bbar^T c^k
// (k <= 2), bbar^T A e = phi4, b^T A e = phi3 + O(h^2), b^T (c . A e) = 3 phi4, b^T A c = phi4.
TEST(OrderConditions, PaperInstancesSAndSchems100) {
  std::set<Printed> paper{
      {"b", "f", "1", 1, 4},         {"b", "f[p]", "1", 2, 3},    {"b", "f[p,p]", "2", 3, 2},
      {"b", "f[p,p,p]", "6", 4, 1},  {"bbar", "f", "1", 2, 3},    {"bbar", "f[p]", "1", 3, 2},
      {"bbar", "f[p,p]", "2", 4, 1}, {"bbar", "f[f]", "1", 4, 1}, {"b", "f[f]", "1", 3, 2},
      {"b", "f[p,f]", "3", 4, 1},    {"b", "f[f[p]]", "1", 4, 1}};
  EXPECT_EQ(conditions_of_order(4), paper);
}

// The paper's compact condition b^T(V) Phi = rho!/gamma phi_rho(V) reads one V for M outside the
// elementary differential (the root's V^j) and inside it (abar(V) on an edge). Through order 4
// only V^0 of an abar-edge enters (the instances above); from order 5 on M inside is its own
// tree: at power 5, b^T A e splits into [V^1] of f[f] and [V^0] of f[M f], two conditions, whose
// sum is the paper's single-V coefficient. The sum is -1/60 = [V^1] (phi2 - phi3)/2, not the
// paper's [V^1] phi3 = -1/120 (docs/errata.md).
TEST(OrderConditions, AnAbarEdgeIsItsOwnTreeFromOrderFive) {
  const auto trees = sen_trees(5);
  const auto conditions = order_conditions(trees, 5);
  auto rhs = [&](const std::string& tree, int j) {
    std::vector<GiNaC::numeric> found;
    for (const OrderCondition& c : conditions)
      if (!c.bbar && c.j == j && trees[c.tree].name == tree) found.push_back(c.rhs);
    EXPECT_EQ(found.size(), 1u) << tree << " at V^" << j;
    return found.empty() ? GiNaC::numeric(0) : found[0];
  };
  const int below_five =
      int(std::count_if(conditions.begin(), conditions.end(),
                        [&](const auto& c) { return !trees[c.tree].nystrom && c.power <= 4; }));
  EXPECT_EQ(below_five, 0);  // negative control of "from order 5": no M inside up to order 4
  const GiNaC::numeric outside = rhs("f[f]", 1), inside = rhs("f[M f]", 0);
  EXPECT_EQ(outside, GiNaC::numeric(-1, 120));
  EXPECT_EQ(inside, GiNaC::numeric(-1, 120));
  EXPECT_EQ(outside + inside, GiNaC::numeric(-1, 60));
  const GiNaC::numeric phi2_v1(-1, 24), phi3_v1(-1, 120);  // [V^1] phi_j = -1/(j+2)!
  EXPECT_EQ(outside + inside, (phi2_v1 - phi3_v1) / 2);
  EXPECT_NE(outside + inside, phi3_v1);
}

// The conditions of one tree and root are the Taylor coefficients of eq. (f): [V^j] with powers
// rho + 2j (b) and rho + 1 + 2j (bbar) up to r, right-hand sides (-1)^j rho!/gamma / (2j+m)!.
TEST(OrderConditions, AreTheTaylorCoefficientsOfEqF) {
  const auto trees = sen_trees(6);
  const auto conditions = order_conditions(trees, 6);
  for (const OrderCondition& c : conditions) {
    const SenTree& t = trees[c.tree];
    EXPECT_EQ(c.power, t.rho() + 2 * c.j + (c.bbar ? 1 : 0));
    GiNaC::numeric m = t.rho() + (c.bbar ? 1 : 0), sign = c.j % 2 ? -1 : 1;
    EXPECT_EQ(c.rhs,
              t.rho_factorial_over_gamma() * sign / GiNaC::factorial(GiNaC::numeric(2 * c.j) + m));
  }
  // b^T e = phi1(V) to h^6: V^0 .. V^2 (powers 1, 3, 5).
  EXPECT_EQ(std::count_if(conditions.begin(), conditions.end(),
                          [&](const OrderCondition& c) { return c.tree == 0 && !c.bbar; }),
            3);
}

}  // namespace
}  // namespace erkn::gen
