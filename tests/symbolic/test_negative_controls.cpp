// Negative controls: the same check functions the tests use must report a perturbed coefficient.
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

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

// b1 + v^2/1000: the symplectic check (exact) names (g) line 1 and 2 for stage 1, also as a series
// at V^2; the order check (which needs only V^0, V^1 up to order 4) does not see it.
TEST(NegativeControls, PerturbedQuadraticTermFailsSymplecticChecks) {
  for (const Method& m : erkn_methods()) {
    Method p = perturbed(m, "b1", "v^2/1000");
    std::vector<Failure> f = exact_failures(symplectic_conditions(p), p);
    const int power = m.digits == 0 ? -1 : 2;  // decimal methods: checked as series
    EXPECT_TRUE(has(f, "(g) line 1, i = 1", power)) << m.name << ":\n" << to_string(f);
    EXPECT_TRUE(has(f, "(g) line 2, i = 1", power)) << m.name << ":\n" << to_string(f);
    std::vector<Failure> g = series_failures(symplectic_conditions(p), p, emitted_series(p, 4));
    EXPECT_TRUE(has(g, "(g) line 1, i = 1", 2)) << m.name << ":\n" << to_string(g);
    if (m.order <= 4)
      EXPECT_TRUE(series_failures(order_conditions(p), p, emitted_series(p, 3)).empty()) << m.name;
  }
}

// The same perturbation against the paper: its comparison reports b1 at V^2 only.
TEST(NegativeControls, PerturbedQuadraticTermFailsPaperComparison) {
  for (const Method& m : paper_methods()) {
    Method p = perturbed(m, "b1", "v^2/1000");
    std::vector<Mismatch> x = paper_mismatches(p, emitted_series(p, 4));
    ASSERT_EQ(x.size(), 1u) << m.name;
    EXPECT_EQ(x[0].coefficient, "b1");
    EXPECT_EQ(x[0].power, 2);
    EXPECT_TRUE(x[0].derived - x[0].printed == Qs(GiNaC::numeric(1, 1000)));
  }
}

// A constant changed by 1/1000: b1 breaks the order condition b^T e = phi1 at V^0 (and (g));
// the last diagonal breaks, for r >= 3, b^T A e = phi3 at V^0 (explicit methods included).
TEST(NegativeControls, PerturbedConstantFailsOrderChecks) {
  for (const Method& m : erkn_methods()) {
    Method p = perturbed(m, "b1", "1/1000");
    std::vector<Failure> f = series_failures(order_conditions(p), p, emitted_series(p, 3));
    EXPECT_TRUE(has(f, "(f) b.e = phi1", 0)) << m.name << ":\n" << to_string(f);
    EXPECT_FALSE(exact_failures(order_conditions(p), p).empty()) << m.name;
    EXPECT_FALSE(exact_failures(symplectic_conditions(p), p).empty()) << m.name;

    Method q = perturbed(m, abar_name(m.s, m.s), "1/1000");
    if (m.order >= 3) {
      f = series_failures(order_conditions(q), q, emitted_series(q, 3));
      EXPECT_TRUE(has(f, "(f) b.Ae = phi3", 0)) << m.name << ":\n" << to_string(f);
    }
  }
}

// A method written with decimal coefficients of `digits` significant digits, as a table of a
// method given by decimals is: every number of c, d and the closed forms evaluated.
Method decimal_copy(Method m, int digits) {
  const long saved = GiNaC::Digits;
  GiNaC::Digits = digits;
  auto decimal = [](const GiNaC::ex& e) {
    std::ostringstream os;
    os << GiNaC::evalf(e);
    return os.str();
  };
  for (int i = 0; i < m.s; ++i) {
    m.c[i] = exact_number(parse(decimal(m.c[i].to_ex())));
    m.d[i] = exact_number(parse(decimal(m.d[i].to_ex())));
  }
  for (std::string& c : m.closed) c = decimal(parse(c));
  GiNaC::Digits = saved;
  m.digits = digits;
  return m;
}

// True if a closed form divides by a function of v (the solved diagonals of the paper: 0/0 at
// v = 0, which decimals turn into a pole).
bool divides_by_v(const GiNaC::ex& e) {
  if (GiNaC::is_a<GiNaC::power>(e) && e.op(0).has(vsym()) && GiNaC::is_a<GiNaC::numeric>(e.op(1)) &&
      GiNaC::ex_to<GiNaC::numeric>(e.op(1)).is_negative())
    return true;
  for (size_t i = 0; i < e.nops(); ++i)
    if (divides_by_v(e.op(i))) return true;
  return false;
}

// Decimal coefficients (every method of the tables with entire coefficients, written with 40
// digits, and any method the tables give by decimals): they meet the order conditions to within
// their tolerance 10^(3 - digits), and a change of b1 of 100 times that, far below double
// precision, fails b^T e = phi1.
TEST(NegativeControls, DecimalCoefficientsAreCheckedBeyondDoublePrecision) {
  int checked = 0;
  for (const Method& exact : erkn_methods()) {
    if (exact.digits == 0 &&
        std::any_of(exact.closed.begin(), exact.closed.end(),
                    [](const std::string& c) { return divides_by_v(parse(c)); }))
      continue;
    const Method m = exact.digits == 0 ? decimal_copy(exact, 40) : exact;
    ++checked;
    EXPECT_TRUE(series_failures(order_conditions(m), m, emitted_series(m, 3)).empty()) << m.name;
    Qs eps(GiNaC::numeric(100) * m.tolerance());
    Method p = perturbed(m, "b1", eps.to_string());
    std::vector<Failure> f = series_failures(order_conditions(p), p, emitted_series(p, 3));
    EXPECT_TRUE(has(f, "(f) b.e = phi1", 0)) << m.name << ":\n" << to_string(f);
  }
  EXPECT_GE(checked, 1);
}

// The last diagonal changed by 1/1000 breaks the paper's diagonal choice and its printed series.
TEST(NegativeControls, PerturbedDiagonalFailsPaperChoices) {
  for (const Method& m : paper_methods()) {
    Method q = perturbed(m, abar_name(m.s, m.s), "1/1000");
    EXPECT_FALSE(exact_failures(defining_conditions(q), q).empty()) << m.name;
    EXPECT_FALSE(paper_mismatches(q, emitted_series(q, 4)).empty()) << m.name;
  }
}

// One printed number changed by 1/1000 (the highest printed power of each coefficient in turn):
// the condition check of the printed series names a violated condition for every b_i, bbar_i and
// abar_ij (j < i), and for the diagonal abar_ii through the paper's diagonal choices.
TEST(NegativeControls, PerturbedPrintedNumberViolatesACondition) {
  for (const Method& m : paper_methods()) {
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
