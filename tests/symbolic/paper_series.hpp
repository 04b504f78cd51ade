// The paper's choices of the diagonal abar_ii and its printed Taylor coefficients of V^0..V^3 of
// every coefficient function of the six methods: Shi, Zhang & Wang, "Diagonal implicit symplectic
// ERKN methods for solving oscillatory Hamiltonian systems", Section 3
// (shared/paper/000_67ac46b702f868a4.txt). 44 coefficient functions in all. Typed in once, exactly
// as printed, in GiNaC syntax: a printed
// "\frac{-4+\sqrt{15}}{72} V" is "(-4+sqrt(15))/72", a printed "- \frac{4+\sqrt{15}}{72} V" is
// "-(4+sqrt(15))/72", and a printed sum of two terms of one power stays a sum. Nothing here is
// simplified or corrected; the tests bring both sides to a + b*sqrt(s).
#pragma once

#include <array>
#include <vector>

namespace erkn::symtest {

struct PaperCoefficient {
  const char* name;              ///< b1, ..., bbar1, ..., abar11, abar21, ...
  std::array<const char*, 4> v;  ///< printed coefficients of V^0, V^1, V^2, V^3
};

/// One of the paper's free choices fixing the diagonal abar_ii, imposed as an equality in V:
/// lhs == rhs, lhs a tree sum of eq. (f) ("b.Ae", "bbar.Ae", "b.cAe") or a GiNaC expression.
struct PaperDiagonal {
  const char* name;
  const char* lhs;
  const char* rhs;
};

struct PaperMethod {
  const char* method;  ///< the paper's name
  const char* where;   ///< where the paper prints the series
  std::vector<PaperDiagonal> diagonal;
  std::vector<PaperCoefficient> coefficients;
};

inline const std::vector<PaperMethod>& paper_series() {
  static const std::vector<PaperMethod> table = {
      {"SERKN1s2(1)",
       "Sec. 3.1, Case one (abar11 = phi0(V)), the series after eq. (n)",
       {{"Sec. 3.1 case one: abar11 = phi0", "abar11", "phi(0,v)"}},
       {
           {"b1", {"1", "-1/8", "1/384", "-1/46080"}},
           {"bbar1", {"1/2", "-1/48", "1/3840", "-1/645120"}},
           {"abar11", {"1", "-1/2", "1/24", "-1/720"}},
       }},
      {"SERKN1s2(2)",
       "Sec. 3.1, Case two (abar11 = bbar1(V))",
       {{"Sec. 3.1 case two: abar11 = bbar1", "abar11", "bbar1"}},
       {
           {"b1", {"1", "-1/8", "1/384", "-1/46080"}},
           {"bbar1", {"1/2", "-1/48", "1/3840", "-1/645120"}},
           {"abar11", {"1/2", "-1/48", "1/3840", "-1/645120"}},
       }},
      {"SERKN2s3",
       "Sec. 3.2, Case one (c1 = 1/5), the series before 'We denote this method by SERKN2s3'",
       {{"Sec. 3.2 case one: abar22 = abar11", "abar22", "abar11"},
        {"(r) last, as equality: b^T A e = phi3", "b.Ae", "phi(3,v)"}},
       {
           {"b1", {"25/52", "-2/13", "8/975", "-64/365625"}},
           {"b2", {"27/52", "-1/78", "1/18954", "-1/11514555"}},
           {"bbar1", {"5/13", "-8/195", "32/24375", "-256/12796875"}},
           {"bbar2", {"3/26", "-1/1053", "1/426465", "-2/725416965"}},
           {"abar11", {"7/312", "589/84240", "9931609/11941020000", "25321869691/290166786000000"}},
           {"abar21", {"5/18", "-169/10935", "28561/110716875", "-9653618/4708235109375"}},
           {"abar22", {"7/312", "589/84240", "9931609/11941020000", "25321869691/290166786000000"}},
       }},
      {"SERKN2s4",
       "Sec. 3.2, Case two (c = (3-+sqrt(3))/6), the series before 'We denote this method by "
       "SERKN2s4'",
       {{"(s) 8th, corrected: bbar^T A e = phi4", "bbar.Ae", "phi(4,v)"},
        {"(s) 9th: b^T A e = phi3", "b.Ae", "phi(3,v)"}},
       {
           {"b1", {"1/2", "-(2+sqrt(3))/24", "(7+4*sqrt(3))/1728", "-(26+15*sqrt(3))/311040"}},
           {"b2", {"1/2", "(-2+sqrt(3))/24", "(7-4*sqrt(3))/1728", "(-26+15*sqrt(3))/311040"}},
           {"bbar1",
            {"(3+sqrt(3))/12", "-(9+5*sqrt(3))/432", "(33+19*sqrt(3))/51840",
             "-(123+71*sqrt(3))/13063680"}},
           {"bbar2",
            {"(3-sqrt(3))/12", "(-9+5*sqrt(3))/432", "(33-19*sqrt(3))/51840",
             "(-123+71*sqrt(3))/13063680"}},
           {"abar11",
            {"(2-sqrt(3))/12", "(-3+2*sqrt(3))/2160", "(6-sqrt(3))/1088640",
             "(15+2*sqrt(3))/195955200"}},
           {"abar21",
            {"1/(2*sqrt(3))", "-1/(36*sqrt(3))", "1/(2160*sqrt(3))", "-1/(272160*sqrt(3))"}},
           {"abar22",
            {"(2-sqrt(3))/12", "(-1+6*sqrt(3))/720", "(6-167*sqrt(3))/1088640",
             "(15+238*sqrt(3))/195955200"}},
       }},
      {"SERKN3s4(1)",
       "Sec. 3.3, Case one, eq. (ekrnD), the series before 'We denote this method by "
       "SERKN3s4(1)'",
       {{"(Schems100) 8th: bbar^T A e = phi4", "bbar.Ae", "phi(4,v)"},
        {"(Schems100) 9th: b^T A e = phi3", "b.Ae", "phi(3,v)"},
        {"(Schems100) 10th: b^T C A e = 3 phi4", "b.cAe", "3*phi(4,v)"}},
       {
           {"b1",
            {"5/18", "-(4+sqrt(15))/72", "(31+8*sqrt(15))/8640", "-(244+63*sqrt(15))/2592000"}},
           {"b2", {"4/9", "-1/18", "1/864", "-1/103680"}},
           {"b3",
            {"5/18", "(-4+sqrt(15))/72", "(31-8*sqrt(15))/8640", "(-244+63*sqrt(15))/2592000"}},
           {"bbar1",
            {"(5+sqrt(15))/36", "-(35+9*sqrt(15))/2160", "(275+71*sqrt(15))/432000",
             "-(2165+559*sqrt(15))/181440000"}},
           {"bbar2", {"2/9", "-1/108", "1/8640", "-1/1451520"}},
           {"bbar3",
            {"(5-sqrt(15))/36", "(-35+9*sqrt(15))/2160", "(275-71*sqrt(15))/432000",
             "(-2165+559*sqrt(15))/181440000"}},
           {"abar11",
            {"(4-sqrt(15))/20", "-3/14000", "-(28+9*sqrt(15))/5040000",
             "-(5871+440*sqrt(15))/16632000000"}},
           {"abar21",
            {"sqrt(15)/36", "-1/(96*sqrt(15))", "1/(12800*sqrt(15))", "-1/(3584000*sqrt(15))"}},
           {"abar22",
            {"(9-2*sqrt(15))/72", "3/11200+1/(96*sqrt(15))", "(29-42*sqrt(15))/8064000",
             "(-3667+330*sqrt(15))/17740800000"}},
           {"abar31",
            {"sqrt(15)/18", "-1/(12*sqrt(15))", "1/(400*sqrt(15))", "-1/(28000*sqrt(15))"}},
           {"abar32",
            {"2/(3*sqrt(15))", "-1/(60*sqrt(15))", "1/(8000*sqrt(15))", "-1/(2240000*sqrt(15))"}},
           {"abar33",
            {"(4-sqrt(15))/20", "(-9+280*sqrt(15))/42000", "-(28+873*sqrt(15))/5040000",
             "(-5871+40535*sqrt(15))/16632000000"}},
       }},
      {"SERKN3s4(2)",
       "Sec. 3.3, Case two, eq. (ekrnE), the two series displays before 'We denote this method "
       "by SERKN3s4(2)'",
       {{"(Schems100) 8th: bbar^T A e = phi4", "bbar.Ae", "phi(4,v)"},
        {"(Schems100) 9th: b^T A e = phi3", "b.Ae", "phi(3,v)"},
        {"(Schems100) 10th: b^T C A e = 3 phi4", "b.cAe", "3*phi(4,v)"}},
       {
           {"b1",
            {"5/18", "(-4+sqrt(15))/72", "(31-8*sqrt(15))/8640", "(-244+63*sqrt(15))/2592000"}},
           {"b2",
            {"5/18", "-(4+sqrt(15))/72", "(31+8*sqrt(15))/8640", "-(244+63*sqrt(15))/2592000"}},
           {"b3", {"4/9", "-1/18", "1/864", "-1/103680"}},
           {"bbar1",
            {"(5-sqrt(15))/36", "(-35+9*sqrt(15))/2160", "(275-71*sqrt(15))/432000",
             "(-2165+559*sqrt(15))/181440000"}},
           {"bbar2",
            {"(5+sqrt(15))/36", "-(35+9*sqrt(15))/2160", "(275+71*sqrt(15))/432000",
             "-(2165+559*sqrt(15))/181440000"}},
           {"bbar3", {"2/9", "-1/108", "1/8640", "-1/1451520"}},
           {"abar11",
            {"(4+sqrt(15))/20", "-3/14000", "(-28+9*sqrt(15))/5040000",
             "(-5871+440*sqrt(15))/16632000000"}},
           {"abar21",
            {"-sqrt(15)/18", "1/(12*sqrt(15))", "-1/(400*sqrt(15))", "1/(28000*sqrt(15))"}},
           {"abar22",
            {"(36+sqrt(15))/180", "-1/(12*sqrt(15))-3/14000", "(-28+831*sqrt(15))/5040000",
             "-(5871+40040*sqrt(15))/16632000000"}},
           {"abar31",
            {"-sqrt(15)/36", "1/(96*sqrt(15))", "-1/(12800*sqrt(15))", "1/(3584000*sqrt(15))"}},
           {"abar32",
            {"sqrt(15)/36", "-1/(96*sqrt(15))", "1/(12800*sqrt(15))", "-1/(3584000*sqrt(15))"}},
           {"abar33", {"1/8", "3/11200", "29/8064000", "-3667/17740800000"}},
       }},
  };
  return table;
}

}  // namespace erkn::symtest
