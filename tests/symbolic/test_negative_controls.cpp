// Negative controls: the same check functions the tests use must report a perturbed coefficient.
#include <gtest/gtest.h>

#include <algorithm>

#include "symbolic_support.hpp"

namespace erkn::symtest {
namespace {

Method perturbed(Method m, const std::string& coefficient, const std::string& term) {
  std::string& c = m.closed[m.index(coefficient)];
  c = "(" + c + ")+" + term;
  return m;
}

bool has(const std::vector<Failure>& f, const std::string& condition, int power) {
  return std::any_of(f.begin(), f.end(), [&](const Failure& x) {
    return x.condition.find(condition) != std::string::npos && x.power == power;
  });
}

// b1 + v^2/1000: the symplectic check (exact) names (g) line 1 and 2 for stage 1, and the paper
// comparison reports b1 at V^2 only; the order check (which needs only V^0, V^1) does not see it.
TEST(NegativeControls, PerturbedQuadraticTermFailsSymplecticAndPaperChecks) {
  for (const Method& m : erkn_methods()) {
    Method p = perturbed(m, "b1", "v^2/1000");
    std::vector<Failure> f = exact_failures(symplectic_conditions(p), p);
    EXPECT_TRUE(has(f, "(g) line 1, i = 1", -1)) << m.name << ":\n" << to_string(f);
    EXPECT_TRUE(has(f, "(g) line 2, i = 1", -1)) << m.name << ":\n" << to_string(f);
    std::vector<Mismatch> x = paper_mismatches(p, emitted_series(p, 4));
    ASSERT_EQ(x.size(), 1u) << m.name;
    EXPECT_EQ(x[0].coefficient, "b1");
    EXPECT_EQ(x[0].power, 2);
    EXPECT_TRUE(x[0].derived - x[0].printed == Qs(GiNaC::numeric(1, 1000)));
    std::vector<Failure> g = series_failures(symplectic_conditions(p), p, emitted_series(p, 4));
    EXPECT_TRUE(has(g, "(g) line 1, i = 1", 2)) << m.name << ":\n" << to_string(g);
  }
}

// A constant changed by 1/1000: b1 breaks the order condition b^T e = phi1 at V^0 (and (g));
// the last diagonal breaks the paper's diagonal choice and, for r >= 3, b^T A e = phi3 at V^0.
TEST(NegativeControls, PerturbedConstantFailsOrderAndDiagonalChecks) {
  for (const Method& m : erkn_methods()) {
    Method p = perturbed(m, "b1", "1/1000");
    std::vector<Failure> f = series_failures(order_conditions(p), p, emitted_series(p, 3));
    EXPECT_TRUE(has(f, "(f) b.e = phi1", 0)) << m.name << ":\n" << to_string(f);
    EXPECT_FALSE(exact_failures(order_conditions(p), p).empty()) << m.name;
    EXPECT_FALSE(exact_failures(symplectic_conditions(p), p).empty()) << m.name;

    std::string last = "abar" + std::to_string(m.s) + std::to_string(m.s);
    Method q = perturbed(m, last, "1/1000");
    EXPECT_FALSE(exact_failures(defining_conditions(q), q).empty()) << m.name;
    EXPECT_FALSE(paper_mismatches(q, emitted_series(q, 4)).empty()) << m.name;
    if (m.order >= 3) {
      f = series_failures(order_conditions(q), q, emitted_series(q, 3));
      EXPECT_TRUE(has(f, "(f) b.Ae = phi3", 0)) << m.name << ":\n" << to_string(f);
    }
  }
}

// One printed number changed by 1/1000 (the highest printed power of each coefficient in turn):
// the condition check of the printed series names a violated condition for every b_i, bbar_i and
// abar_ij (j < i), and for the diagonal abar_ii through the paper's diagonal choices.
TEST(NegativeControls, PerturbedPrintedNumberViolatesACondition) {
  for (const Method& m : erkn_methods()) {
    std::vector<Condition> conditions = symplectic_conditions(m);
    for (const Condition& c : defining_conditions(m)) conditions.push_back(c);
    for (size_t k = 0; k < m.names.size(); ++k) {
      std::vector<Series> printed = printed_series(m);
      printed[k][3] = printed[k][3] + Qs(GiNaC::numeric(1, 1000));
      std::vector<Failure> f = series_failures(conditions, m, printed);
      ASSERT_FALSE(f.empty()) << m.name << " " << m.names[k];
      EXPECT_TRUE(std::all_of(f.begin(), f.end(), [](const Failure& x) { return x.power == 3; }))
          << m.name << " " << m.names[k] << ":\n"
          << to_string(f);
    }
  }
}

}  // namespace
}  // namespace erkn::symtest
