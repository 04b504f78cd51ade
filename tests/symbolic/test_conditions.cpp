// The emitted methods against the paper's conditions: symplectic (Theorem 2, eq. (g)), order
// (Theorem 1, eq. (f)), the diagonal choices of Section 3, and their V -> 0 limits as RKN methods.
#include <gtest/gtest.h>

#include <algorithm>

#include "symbolic_support.hpp"

namespace erkn::symtest {
namespace {

TEST(Conditions, SymplecticConditionsHoldIdentically) {
  for (const Method& m : erkn_methods()) {
    std::vector<Condition> g = symplectic_conditions(m);
    ASSERT_EQ(int(g.size()), 2 * m.s + m.s * (m.s - 1) / 2) << m.name;
    std::vector<Failure> f = exact_failures(g, m);
    EXPECT_TRUE(f.empty()) << m.name << ":\n" << to_string(f);
  }
}

TEST(Conditions, DiagonalChoicesOfThePaperHoldIdentically) {
  for (const Method& m : paper_methods()) {
    std::vector<Condition> c = defining_conditions(m);
    ASSERT_EQ(int(c.size()), m.s) << m.name;
    std::vector<Failure> f = exact_failures(c, m);
    EXPECT_TRUE(f.empty()) << m.name << ":\n" << to_string(f);
  }
}

TEST(Conditions, OrderConditionsHoldToClaimedOrder) {
  for (const Method& m : erkn_methods()) {
    std::vector<Condition> c = order_conditions(m);
    // The instances of (f) the paper lists: (i) for order 2 (3 conditions), (r) for order 3 (6),
    // (s) and (Schems100) for order 4 (11). Trees of order 5 and more are not modelled here (the
    // generator certifies them); a method of higher order is checked on these 11, each to the
    // power of V its order requires.
    const int listed[] = {0, 1, 3, 6, 11};
    ASSERT_GE(m.order, 1) << m.name;
    ASSERT_EQ(int(c.size()), listed[std::min(m.order, 4)]) << m.name;
    // Series by GiNaC's series() of the emitted closed forms ...
    std::vector<Failure> f = series_failures(c, m, emitted_series(m, 3));
    EXPECT_TRUE(f.empty()) << m.name << " (GiNaC series):\n" << to_string(f);
    // ... and by the exact normal form, as a cross-check.
    f = exact_failures(c, m);
    EXPECT_TRUE(f.empty()) << m.name << " (normal form):\n" << to_string(f);
  }
}

// The trees with an abar-edge in two matrices, V^j W^k, to the power of h the claimed order
// requires (beyond V^0 W^0 from order 5 on, and for b^T A e at V^0 W^1 or V^1 W^0 from order 5).
TEST(Conditions, EdgeTreesHoldInTwoMatrices) {
  for (const Method& m : erkn_methods()) {
    std::vector<Failure> f = edge_failures(m, emitted_series(m, 4));
    EXPECT_TRUE(f.empty()) << m.name << ":\n" << to_string(f);
  }
}

// The exact weights are those of the classical trees at V^0 W^0 (rho!/gamma phi_rho(0)), and in a
// single V they are not the paper's phi_rho(V): b^T A e has (phi2(V) - phi3(V))/2, whose V^1
// coefficient -1/60 differs from phi3's -1/120.
TEST(Conditions, EdgeWeightsAreTheExactFlowsNotThePapersPhi) {
  const std::vector<EdgeTree> t = edge_trees();
  EXPECT_TRUE(edge_weight(t[0], 0, 0) == Qs(GiNaC::numeric(1, 6)));
  EXPECT_TRUE(edge_weight(t[1], 0, 0) == Qs(GiNaC::numeric(1, 24)));
  EXPECT_TRUE(edge_weight(t[2], 0, 0) == Qs(GiNaC::numeric(1, 8)));
  EXPECT_TRUE(edge_weight(t[3], 0, 0) == Qs(GiNaC::numeric(1, 24)));
  Qs single_v = edge_weight(t[0], 1, 0) + edge_weight(t[0], 0, 1);
  EXPECT_TRUE(single_v == Qs(GiNaC::numeric(-1, 60)));
  EXPECT_TRUE(phi_series(3, Qs(1), 2)[1] == Qs(GiNaC::numeric(-1, 120)));
}

// The claimed order is not an understatement: for the methods of order 2 and 3 a condition of
// order r + 1 fails (at V^0). (For order 4 the trees of order 5 are not modelled here.)
TEST(Conditions, ClaimedOrderIsSharpBelowFour) {
  for (Method m : erkn_methods()) {
    if (m.order >= 4) continue;
    const std::string name = m.name;
    m.order += 1;
    std::vector<Failure> f = series_failures(order_conditions(m), m, emitted_series(m, 3));
    EXPECT_FALSE(f.empty()) << name << " satisfies the order conditions of order " << m.order;
  }
}

// The V -> 0 limits: the emitted RKN tables are the V^0 values of the ERKN coefficients and
// satisfy the classical RKN order conditions (Hairer-Norsett-Wanner, Table II.14.3) of their
// order and the symplecticity conditions of Suris for RKN methods (bbar_i = b_i (1 - c_i),
// b_i (bbar_j - a_ij) = b_j (bbar_i - a_ji)).
TEST(Conditions, RknLimitsSatisfyClassicalRknConditions) {
  int limits = 0;
  for (const Method& m : erkn_methods()) {
    if (m.limit.empty()) continue;
    ++limits;
    Method r = find_method(m.limit);
    ASSERT_TRUE(r.rkn) << r.name;
    EXPECT_EQ(r.s, m.s);
    EXPECT_EQ(r.order, m.order);
    std::vector<Series> limit = emitted_series(m, 1), constants;
    for (size_t k = 0; k < r.closed.size(); ++k) {
      Qs value = exact_number(parse(r.closed[k]));
      constants.push_back({value});
      EXPECT_TRUE(r.negligible(value - limit[k][0])) << r.name << " " << r.names[k];
    }
    for (int i = 0; i < m.s; ++i)
      EXPECT_TRUE(r.negligible(r.c[i] - m.c[i]) && r.negligible(r.d[i] - m.d[i])) << r.name;
    std::vector<Failure> f = series_failures(classical_rkn_conditions(r), r, constants);
    EXPECT_TRUE(f.empty()) << r.name << ":\n" << to_string(f);

    auto a = [&](int i, int j) { return j > i ? Qs(0) : constants[r.index(abar_name(i, j))][0]; };
    auto b = [&](int i) { return constants[r.index("b" + std::to_string(i))][0]; };
    auto bb = [&](int i) { return constants[r.index("bbar" + std::to_string(i))][0]; };
    for (int i = 1; i <= r.s; ++i) {
      EXPECT_TRUE(r.negligible(bb(i) - b(i) * (Qs(1) - r.c[i - 1]))) << r.name << " i=" << i;
      for (int j = 1; j <= r.s; ++j)
        EXPECT_TRUE(r.negligible(b(i) * (bb(j) - a(i, j)) - b(j) * (bb(i) - a(j, i))))
            << r.name << " i=" << i << " j=" << j;
    }
  }
  // Every method of the paper has its V -> 0 limit in the tables.
  EXPECT_GE(limits, int(paper_methods().size()));
}

}  // namespace
}  // namespace erkn::symtest
