// The paper's printed formulas and conditions (not its numbers) against the emitted methods: the
// traps (Theorem 2 with j = i, the 8th condition of (s), the brackets of (t) and (ekrnB)) and the
// printed formulas that are right.
#include <gtest/gtest.h>

#include <algorithm>

#include "symbolic_support.hpp"

using GiNaC::ex;
using GiNaC::pow;

namespace erkn::symtest {
namespace {

std::string I(int i) { return std::to_string(i); }

ex subst_nodes(const ex& e, const Method& m) {
  GiNaC::exmap nodes;
  for (int i = 0; i < m.s; ++i) nodes[sym("c" + I(i + 1))] = m.c[i].to_ex();
  for (int i = 0; i < m.s; ++i) nodes[sym("d" + I(i + 1))] = m.d[i].to_ex();
  return e.subs(nodes);
}

bool equals_emitted(const std::string& formula, const std::string& coefficient, const Method& m) {
  return identically_equal(exact(parse(formula), m), exact(sym(coefficient), m));
}

// Theorem 2, eq. (g), third line, is printed for j = 1, ..., i. With j = i it reads
// bbar_i b_i = bbar_i b_i + d_i abar_ii, i.e. d_i abar_ii = 0: with d_i != 0 every diagonal
// coefficient would vanish. Every method of the paper has abar_ii(0) != 0, and a method with
// abar_ii = 0 could not meet the order conditions it claims (b^T A e = phi3 at V^0 for r >= 3).
TEST(PaperFormulas, TheoremTwoThirdConditionWithJEqualIForcesZeroDiagonal) {
  for (const Method& m : paper_methods()) {
    std::vector<Series> series = emitted_series(m, 4);
    for (int i = 1; i <= m.s; ++i) {
      ASSERT_FALSE(m.d[i - 1].is_zero());
      Condition printed{"(g) line 3 as printed with j = i = " + I(i),
                        parse("bbar" + I(i) + "*b" + I(i) + "-(bbar" + I(i) + "*b" + I(i) + "+d" +
                              I(i) + "*abar" + I(i) + I(i) + ")"),
                        4};
      EXPECT_TRUE((printed.residual + sym("d" + I(i)) * sym("abar" + I(i) + I(i))).is_zero());
      std::vector<Failure> f = exact_failures({{printed.name, printed.residual, kIdentity}}, m);
      EXPECT_EQ(f.size(), 1u) << m.name << " satisfies " << printed.name;
      f = series_failures({printed}, m, series);
      ASSERT_EQ(f.size(), 1u) << m.name;
      EXPECT_EQ(f[0].power, 0) << m.name << ":\n" << to_string(f);
    }
    if (m.order >= 3) {
      std::vector<Series> zero_diagonal = series;
      for (int i = 1; i <= m.s; ++i)
        zero_diagonal[m.index("abar" + I(i) + I(i))] = Series(4, Qs(0));
      std::vector<Failure> f = series_failures(order_conditions(m), m, zero_diagonal);
      bool bAe_fails_at_0 = std::any_of(f.begin(), f.end(), [](const Failure& x) {
        return x.condition.find("b.Ae = phi3") != std::string::npos && x.power == 0;
      });
      EXPECT_TRUE(bAe_fails_at_0) << m.name << " with abar_ii = 0:\n" << to_string(f);
    }
  }
}

// (s), 8th condition, as printed: b1 abar11 + b2 (abar21 + abar22) = phi4 + O(h). Its left side is
// that of the 9th condition (= phi3 + O(h^2)), so at V^0 it demands 1/24 = 1/6: no method
// satisfies both. The intended condition is bbar^T A e = phi4 (as in the 8th of (Schems100)), and
// the paper's own formulas for abar11, abar22 of SERKN2s4 (after (ppmn)) solve exactly that.
TEST(PaperFormulas, EighthConditionOfSAsPrintedContradictsTheNinth) {
  Method m = find_method("SERKN2s4");
  ex lhs8 = parse("b1*abar11+b2*(abar21+abar22)");
  ex lhs9 = parse("b1*abar11+b2*(abar21+abar22)");
  ex v = vsym();
  EXPECT_TRUE((lhs8 - lhs9).is_zero());
  EXPECT_TRUE((lhs9 - tree_sum(m, "b.Ae")).expand().is_zero());
  // phi3(0) - phi4(0) = 1/6 - 1/24 = 1/8 != 0: the two printed conditions contradict at V^0.
  EXPECT_TRUE(phi_series(3, Qs(1), 1)[0] - phi_series(4, Qs(1), 1)[0] == Qs(GiNaC::numeric(1, 8)));

  std::vector<Series> series = emitted_series(m, 4);
  std::vector<Failure> f = series_failures(
      {{"(s) 8th as printed: b^T A e = phi4", lhs8 - gen::phi(4, v), 1}}, m, series);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0].power, 0);
  EXPECT_EQ(f[0].value, "1/8");
  // The 9th and the corrected 8th hold identically.
  f = exact_failures({{"(s) 9th", lhs9 - gen::phi(3, v), kIdentity},
                      {"(s) 8th corrected", tree_sum(m, "bbar.Ae") - gen::phi(4, v), kIdentity}},
                     m);
  EXPECT_TRUE(f.empty()) << to_string(f);
  // The paper's formulas after (ppmn) are the emitted abar11, abar22.
  EXPECT_TRUE(equals_emitted("(bbar2*phi(3,v)-b2*phi(4,v))/(-b2*bbar1+b1*bbar2)", "abar11", m));
  EXPECT_TRUE(
      equals_emitted("(abar21*b2*bbar1-abar21*b1*bbar2-bbar1*phi(3,v)+b1*phi(4,v))/"
                     "(-b2*bbar1+b1*bbar2)",
                     "abar22", m));
}

// (t) prints bbar_i = b_i (1 - c_i) phi1((1 - c_i)^2 V) / phi0(1 - c_i)^2 V: read as printed, the
// denominator is the constant phi0(1 - c_i), squared, times V, so bbar_i ~ 1/V at V = 0 and the
// first symplectic condition (g) fails at V^0 by d_i (1 - c_i) / phi0(1 - c_i)^2. With the bracket
// phi0((1 - c_i)^2 V) the formula is the emitted bbar_i.
TEST(PaperFormulas, FormulaTAsPrintedHasMisplacedBrackets) {
  const ex v = vsym();
  for (const char* name : {"SERKN2s3", "SERKN2s4"}) {
    Method m = find_method(name);
    for (int i = 1; i <= m.s; ++i) {
      ex c = m.c[i - 1].to_ex(), d = m.d[i - 1].to_ex();
      ex b = parse(m.closed[m.index("b" + I(i))]);
      ex printed = b * (1 - c) * gen::phi(1, pow(1 - c, 2) * v) / (pow(gen::phi(0, 1 - c), 2) * v);
      ex laurent = GiNaC::series_to_poly(printed.series(v == 0, 2));
      EXPECT_EQ(laurent.ldegree(v), -1) << name << " i=" << i;
      ex g1 = gen::phi(0, v) * b + v * gen::phi(1, v) * printed - d * gen::phi(0, c * c * v);
      ex at0 = GiNaC::series_to_poly(g1.series(v == 0, 2)).expand().coeff(v, 0);
      ex expected = d * (1 - c) / pow(gen::phi(0, 1 - c), 2);
      EXPECT_TRUE((at0 - expected).expand().is_zero()) << name << ": " << at0;
      EXPECT_GT(GiNaC::ex_to<GiNaC::numeric>(GiNaC::evalf(at0)).to_double(), 0.1) << name;

      std::string one_minus_c = "(1-c" + I(i) + ")";
      EXPECT_TRUE(equals_emitted("b" + I(i) + "*" + one_minus_c + "*phi(1," + one_minus_c +
                                     "^2*v)/phi(0," + one_minus_c + "^2*v)",
                                 "bbar" + I(i), m))
          << name;
      EXPECT_TRUE(equals_emitted("d" + I(i) + "*phi(0,(-1+c" + I(i) + ")^2*v)", "b" + I(i), m))
          << name;
    }
  }
}

int bracket_balance(const std::string& s) {
  return int(std::count(s.begin(), s.end(), '(')) - int(std::count(s.begin(), s.end(), ')'));
}

const char* kD = "(b2*b3*bbar1*(c2-c3)+b1*(b2*bbar3*(c1-c2)+b3*bbar2*(-c1+c3)))";

// (ekrnB): each printed numerator is split over two or three fractions with its brackets opened in
// one and closed in another (so no single fraction is an expression), abar11 writes c2(V), c3(V)
// for the constant nodes, and abar33 writes a32 for abar32. Repaired (brackets joined, c_i(V) read
// as c_i, a32 as abar32) the three formulas are the emitted diagonals of both SERKN3s4 methods;
// with a32 read as a coefficient the tableau does not have (a32 = 0), abar33 changes and the 9th
// condition of (Schems100), b^T A e = phi3, fails at V^0.
TEST(PaperFormulas, DiagonalFormulasEkrnBAsPrintedAreGarbled) {
  // Numerators of the printed fractions, transcribed with their brackets (\dfrac by \dfrac).
  const std::vector<std::pair<const char*, int>> printed_fractions = {
      {"((-b2*bbar3*c2+b3*bbar2*c3)*phi(3,v)", +1},                       // abar11
      {"(3*b2*bbar3+b3*(-3*bbar2+b2*c2(v)-b2*c3(v)))*phi(4,v))", -1},     // abar11
      {"abar21*(b1*(b2*bbar3*(-c1+c2)+b3*bbar2*(c1-c3)", +2},             // abar22
      {"b2*b3*bbar1*(-c2+c3))+(b1*bbar3*c1-b3*bbar1*c3)*phi(3,v)", -1},   // abar22
      {"(abar31+a32)*(b1*(b2*bbar3*(-c1+c2)+b3*bbar2*(c1-c3)", +2},       // abar33
      {"b2*b3*bbar1*(-c2+c3))+(-b1*bbar2*c1+b2*bbar1*c2)*phi(3,v)", -1},  // abar33
      {"3*b1*bbar2+b2*(-3*bbar1+b1*c1-b1*c2))*phi(4,v)", -1},             // abar33
  };
  for (const auto& [text, balance] : printed_fractions)
    EXPECT_EQ(bracket_balance(text), balance) << text;

  const std::string abar11 =
      std::string(
          "((-b2*bbar3*c2+b3*bbar2*c3)*phi(3,v)+(3*b2*bbar3+b3*(-3*bbar2+b2*c2-b2*c3))*"
          "phi(4,v))/") +
      kD;
  const std::string abar22 =
      std::string(
          "(abar21*(b1*(b2*bbar3*(-c1+c2)+b3*bbar2*(c1-c3))+b2*b3*bbar1*(-c2+c3))+"
          "(b1*bbar3*c1-b3*bbar1*c3)*phi(3,v)+(-3*b1*bbar3+b3*(3*bbar1-b1*c1+b1*c3))*"
          "phi(4,v))/") +
      kD;
  const std::string abar33_with = [](const std::string& a32) {
    return "((abar31+" + a32 +
           ")*(b1*(b2*bbar3*(-c1+c2)+b3*bbar2*(c1-c3))+b2*b3*bbar1*(-c2+c3))+"
           "(-b1*bbar2*c1+b2*bbar1*c2)*phi(3,v)+(3*b1*bbar2+b2*(-3*bbar1+b1*c1-b1*c2))*"
           "phi(4,v))/" +
           kD;
  }("abar32");
  for (const char* name : {"SERKN3s4(1)", "SERKN3s4(2)"}) {
    Method m = find_method(name);
    EXPECT_TRUE(equals_emitted(abar11, "abar11", m)) << name;
    EXPECT_TRUE(equals_emitted(abar22, "abar22", m)) << name;
    EXPECT_TRUE(equals_emitted(abar33_with, "abar33", m)) << name;

    // a32 read as an entry of its own, absent from the tableau: 0.
    std::string with_zero = abar33_with;
    with_zero.replace(with_zero.find("abar31+abar32"), 13, "abar31+0");
    gen::Rational wrong = exact(parse(with_zero), m);
    EXPECT_FALSE(identically_equal(wrong, exact(sym("abar33"), m))) << name;
    std::vector<Series> series = emitted_series(m, 4);
    series[m.index("abar33")] = gen::taylor(wrong, 4);
    std::vector<Failure> f = series_failures(defining_conditions(m), m, series);
    bool ninth_at_0 = std::any_of(f.begin(), f.end(), [](const Failure& x) {
      return x.condition.find("9th") != std::string::npos && x.power == 0;
    });
    EXPECT_TRUE(ninth_at_0) << name << ":\n" << to_string(f);
  }
}

// The printed formulas that are right: (j)/(t) for b_i, (scvg) for b_i and bbar_i, (u)/(ekrnA)
// for abar_ij (j < i), Sec. 3.2 case one for abar11 = abar22, and the node formulas (x), (ppmn),
// (ekrnC) with (ekrnD), (ekrnE).
TEST(PaperFormulas, PrintedFormulasThatAreRightReproduceEmittedMethods) {
  for (const Method& m : paper_methods()) {
    for (int i = 1; i <= m.s; ++i) {
      std::string c = "c" + I(i), d = "d" + I(i);
      EXPECT_TRUE(equals_emitted(d + "*phi(0,(1-" + c + ")^2*v)", "b" + I(i), m)) << m.name;
      EXPECT_TRUE(equals_emitted(d + "*(1-" + c + ")*phi(1,(1-" + c + ")^2*v)", "bbar" + I(i), m))
          << m.name;
      std::string p0c = "phi(0," + c + "^2*v)", p1c = "phi(1," + c + "^2*v)";
      EXPECT_TRUE(equals_emitted("b" + I(i) + "*(" + p0c + "*phi(1,v)-" + c + "*phi(0,v)*" + p1c +
                                     ")/(phi(0,v)*" + p0c + "+" + c + "*v*phi(1,v)*" + p1c + ")",
                                 "bbar" + I(i), m))
          << m.name << " (scvg) bbar" << i;
      EXPECT_TRUE(equals_emitted(
          d + "*(phi(0,v)*" + p0c + "+" + c + "*v*phi(1,v)*" + p1c + ")/(phi(0,v)^2+v*phi(1,v)^2)",
          "b" + I(i), m))
          << m.name << " (scvg) b" << i;
      for (int j = 1; j < i; ++j)
        EXPECT_TRUE(
            equals_emitted("(b" + I(i) + "*bbar" + I(j) + "-b" + I(j) + "*bbar" + I(i) + ")/" + d,
                           "abar" + I(i) + I(j), m))
            << m.name << " (ekrnA) abar" << i << j;
    }
  }
  Method m2 = find_method("SERKN2s3");
  EXPECT_TRUE(equals_emitted("(-abar21*b2+phi(3,v))/(b1+b2)", "abar11", m2));
  EXPECT_TRUE(equals_emitted("(-abar21*b2+phi(3,v))/(b1+b2)", "abar22", m2));

  auto node = [](const std::string& formula, const Method& m) {
    return exact_number(subst_nodes(parse(formula), m));
  };
  for (const char* name : {"SERKN1s2(1)", "SERKN1s2(2)"}) {
    Method m = find_method(name);
    EXPECT_TRUE(m.c[0] == Qs(GiNaC::numeric(1, 2)) && m.d[0] == Qs(1)) << name;  // after (n)
  }
  // (x): c1 = 1/5 -> c2 = 7/9, d1 = 25/52, d2 = 27/52.
  EXPECT_TRUE(m2.c[0] == Qs(GiNaC::numeric(1, 5)));
  EXPECT_TRUE(node("(2-3*c1)/(3-6*c1)", m2) == m2.c[1]);
  EXPECT_TRUE(m2.c[1] == Qs(GiNaC::numeric(7, 9)));
  for (const char* name : {"SERKN2s3", "SERKN2s4"}) {  // (x) and (ppmn)
    Method m = find_method(name);
    EXPECT_TRUE(node("(1-2*c2)/(2*(c1-c2))", m) == m.d[0]) << name;
    EXPECT_TRUE(node("(-1+2*c1)/(2*(c1-c2))", m) == m.d[1]) << name;
  }
  EXPECT_TRUE(m2.d[0] == Qs(GiNaC::numeric(25, 52)) && m2.d[1] == Qs(GiNaC::numeric(27, 52)));
  Method m4 = find_method("SERKN2s4");
  EXPECT_TRUE(m4.d[0] == Qs(GiNaC::numeric(1, 2)) && m4.d[1] == Qs(GiNaC::numeric(1, 2)));
  for (const char* name : {"SERKN3s4(1)", "SERKN3s4(2)"}) {  // (ekrnC)
    Method m = find_method(name);
    EXPECT_TRUE(node("(3-4*c1-4*c2+6*c1*c2)/(4-6*c1-6*c2+12*c1*c2)", m) == m.c[2]) << name;
    EXPECT_TRUE(node("(2-3*c3+c2*(-3+6*c3))/(6*(c1-c2)*(c1-c3))", m) == m.d[0]) << name;
    EXPECT_TRUE(node("(-2+c1*(3-6*c3)+3*c3)/(6*(c1-c2)*(c2-c3))", m) == m.d[1]) << name;
    EXPECT_TRUE(node("(-2+c1*(3-6*c2)+3*c2)/(6*(c1-c3)*(-c2+c3))", m) == m.d[2]) << name;
  }
  // (ekrnD): c3 = (5+sqrt(15))/10; (ekrnE): c3 = 1/2.
  EXPECT_TRUE(find_method("SERKN3s4(1)").c[2] == exact_number(parse("(5+sqrt(15))/10")));
  EXPECT_TRUE(find_method("SERKN3s4(2)").c[2] == Qs(GiNaC::numeric(1, 2)));
}

}  // namespace
}  // namespace erkn::symtest
