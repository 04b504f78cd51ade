// Modified kicks in the order theory (certify.hpp): a stage whose force is
// d_i f(Q_i) + h^2 et_i f'(Q_i) f(Q_i). The weights of the f' f term are validated against the
// composition that realises it as a limit, and against the published orders of Chin's method.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "certify.hpp"
#include "derive.hpp"
#include "spec.hpp"

namespace erkn::gen {
namespace {

using GiNaC::numeric;
using Series = std::vector<Qs>;

constexpr int kTerms = 4, kPower = 8;

// A deterministic "generic" rational series: no structure the weights could lean on.
Series generic(int seed) {
  Series out;
  for (int k = 0; k < kTerms; ++k) out.push_back(Qs(numeric((seed * 7 + k * 5) % 11 - 5, 7 + k)));
  return out;
}

// An implicit 3-stage tableau (abar_ii != 0), not symplectic, with modified kicks everywhere
// except on the diagonal of abar_mod (so that the limit below stays lower triangular).
SeriesTableau generic_modified() {
  SeriesTableau t;
  t.s = 3;
  t.c = {Qs(numeric(1, 5)), Qs(numeric(1, 2)), Qs(numeric(7, 8))};
  for (int i = 0; i < 3; ++i) {
    t.b.push_back(generic(i)), t.bbar.push_back(generic(i + 3));
    t.b_mod.push_back(generic(i + 6)), t.bbar_mod.push_back(generic(i + 9));
    for (int j = 0; j <= i; ++j) {
      t.abar.push_back(generic(12 + 3 * i + j));
      t.abar_mod.push_back(j < i ? generic(24 + 3 * i + j) : Series(kTerms, Qs(0)));
    }
  }
  return t;
}

// The plain 2s-stage tableau that realises t's modified kicks with a step delta: stage j' = 2j+1
// sits at Q_j + delta h^2 f(Q_j) (row j plus delta at column j), and every weight w_mod of
// f'(Q_j) f(Q_j) becomes w_mod/delta on f(Q_j') and -w_mod/delta on f(Q_j): as delta -> 0 its
// expansion tends to t's (the difference is O(delta)).
SeriesTableau limit_composition(const SeriesTableau& t, const Qs& delta) {
  const Qs inv = delta.inverse();
  auto scaled = [](const Series& x, const Qs& k) {
    Series out;
    for (const Qs& v : x) out.push_back(v * k);
    return out;
  };
  auto minus = [](const Series& x, const Series& y) {
    Series out;
    for (size_t k = 0; k < x.size(); ++k) out.push_back(x[k] - y[k]);
    return out;
  };
  SeriesTableau p;
  p.s = 2 * t.s;
  std::vector<std::vector<Series>> A(p.s, std::vector<Series>(p.s, Series(kTerms, Qs(0))));
  for (int j = 0; j < t.s; ++j) {
    p.c.push_back(t.c[j]), p.c.push_back(t.c[j]);
    p.b.push_back(minus(t.b[j], scaled(t.b_mod[j], inv))), p.b.push_back(scaled(t.b_mod[j], inv));
    p.bbar.push_back(minus(t.bbar[j], scaled(t.bbar_mod[j], inv)));
    p.bbar.push_back(scaled(t.bbar_mod[j], inv));
    for (int l = 0; l <= j; ++l) {
      const int jl = j * (j + 1) / 2 + l;
      A[2 * j][2 * l] = minus(t.abar[jl], scaled(t.abar_mod[jl], inv));
      if (l < j) A[2 * j][2 * l + 1] = scaled(t.abar_mod[jl], inv);
    }
    A[2 * j + 1] = A[2 * j];
    A[2 * j + 1][2 * j][0] = A[2 * j + 1][2 * j][0] + delta;
  }
  for (int i = 0; i < p.s; ++i)
    for (int j = 0; j <= i; ++j) p.abar.push_back(A[i][j]);
  return p;
}

double max_difference(const std::vector<Qs>& x, const std::vector<Qs>& y) {
  double m = 0;
  for (size_t k = 0; k < x.size(); ++k) m = std::max(m, std::abs((x[k] - y[k]).to_double()));
  return m;
}

std::vector<Qs> all_residuals(const SeriesTableau& t) {
  const auto trees = sen_trees(kPower);
  return residuals(t, trees, order_conditions(trees, kPower));
}

// Every condition up to h^8 (all SEN-trees, every power of V) agrees with the limit to O(delta).
TEST(ModifiedKicks, WeightsAreTheLimitOfTheComposition) {
  const SeriesTableau t = generic_modified();
  const std::vector<Qs> r = all_residuals(t);
  const Qs delta(numeric(1) / numeric(10).power(30));
  EXPECT_LT(max_difference(r, all_residuals(limit_composition(t, delta))), 1e-20);
  // The difference is O(delta), not an accident of one delta: at 1e-15 it is larger.
  const double coarse = max_difference(
      r, all_residuals(limit_composition(t, Qs(numeric(1) / numeric(10).power(15)))));
  EXPECT_GT(coarse, 1e-20);
  EXPECT_LT(coarse, 1e-5);
}

// Negative control: the same comparison fails when the modified weights are off (b_mod doubled).
TEST(ModifiedKicks, LimitNegativeControl) {
  SeriesTableau t = generic_modified();
  const SeriesTableau p = limit_composition(t, Qs(numeric(1) / numeric(10).power(30)));
  for (Series& row : t.b_mod)
    for (Qs& x : row) x = x * Qs(2);
  EXPECT_GT(max_difference(all_residuals(t), all_residuals(p)), 1e-3);
}

// Chin's 4th-order force-gradient method C (Chin, Phys. Lett. A 226 (1997) 344; Omelyan,
// Mryglod & Folk's 4MN2F1GV): kicks 1/6, 2/3, 1/6 at c = 0, 1/2, 1, the middle one by the
// force 2/3 grad(U - h^2/48 |grad U|^2), i.e. e = -1/72 in p -= h (d grad U + h^2 e grad(|grad
// U|^2)). (By hand: the kicks give p its h^3 f'f term 5/36 of the exact 1/6 (f = -grad U), and -h^3
// e grad(|grad U|^2) = -2 e h^3 f'f supplies the missing 1/36.)
Certificate chin(const numeric& e_middle) {
  const std::vector<Qs> c{Qs(0), Qs(numeric(1, 2)), Qs(1)};
  const std::vector<Qs> d{Qs(numeric(1, 6)), Qs(numeric(2, 3)), Qs(numeric(1, 6))};
  const std::vector<Qs> e{Qs(0), Qs(e_middle), Qs(0)};
  return certify(explicit_series(c, d, 5, e), false, kPower);
}

TEST(ModifiedKicks, ChinsMethodIsOrderFour) {
  const Certificate cert = chin(numeric(-1, 72));
  EXPECT_EQ(cert.order, 4);
  // Its first failure is at h^5; for H = A + eps B the eps^1 terms (plain Simpson quadrature of
  // the kicks) are order 4 as well.
  ASSERT_NE(cert.first_failure(), nullptr);
  EXPECT_EQ(cert.first_failure()->condition.power, 5);
  EXPECT_EQ(cert.generalized.at(0), 4);
}

// Negative controls: the opposite sign (the sign MDevolve's G coefficient has), and
// -1/72 + 1/1000, fail at h^3 at the tree f[f] (the
// first condition the modified kick enters), and without the modified kick the method is order 2.
TEST(ModifiedKicks, ChinPerturbedFailsAtNamedTree) {
  for (const numeric& e : {numeric(1, 72), numeric(-1, 72) + numeric(1, 1000), numeric(0)}) {
    const Certificate cert = chin(e);
    EXPECT_EQ(cert.order, 2) << e;
    ASSERT_NE(cert.first_failure(), nullptr);
    EXPECT_EQ(cert.trees[cert.first_failure()->condition.tree].name, "f[f]") << e;
  }
}

MethodSpec spec_of(const std::string& text) {
  std::istringstream in(text);
  return read_specs(in).at(0);
}

const char* const kChinSpec =
    "method C\nkind explicit\nsource test\nstages 3\norder 4\nc 0, 1/2, 1\n"
    "kick 1/6, 2/3, 1/6\n";

// The spec language: `modified` is read, and refused where it has no meaning.
TEST(ModifiedKicks, SpecRefusesWhatItCannotMean) {
  EXPECT_EQ(spec_of(std::string(kChinSpec) + "modified 0, -1/72, 0\n").e.size(), 3u);
  for (const std::string& bad :
       {std::string(kChinSpec) + "modified 0, -1/72\n",            // one per stage
        std::string(kChinSpec) + "rkn R\nmodified 0, -1/72, 0\n",  // no V -> 0 limit
        std::string("method C\nsource t\nstages 1\norder 2\nc 1/2\nd 1\nrkn R\n"
                    "diagonal abar11 == 0\nmodified 1\n")}) {  // kind erkn
    EXPECT_THROW(spec_of(bad), std::runtime_error) << bad;
  }
}

// Decimals of e are polished with c and d: Chin's e = -1/72 written to 17 digits becomes -1/72
// to the working precision, and the method certifies order 4.
TEST(ModifiedKicks, DecimalsOfEArePolished) {
  Derived m = derive(spec_of(std::string(kChinSpec) + "modified 0, -0.013888888888888889, 0\n"));
  ASSERT_EQ(m.e.size(), 3u);
  EXPECT_TRUE(m.e[1].is_approx());
  EXPECT_LT(std::abs((m.e[1] + Qs(numeric(1, 72))).to_double()), 1e-45);
  EXPECT_EQ(m.certificate.order, 4);
  // Negative control: a wrong digit (beyond rounding) is refused, naming the tree f[f].
  try {
    derive(spec_of(std::string(kChinSpec) + "modified 0, -0.0139, 0\n"));
    ADD_FAILURE() << "a wrong e was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("tree f[f]"), std::string::npos) << e.what();
  }
}

// A pure modified kick (d = 0, a corrector) is a stage: Strang with correctors e = -1/24 at
// c = 0 and 1 (SABAC_1) removes the eps^2 h^3 error; without them it stays.
TEST(ModifiedKicks, CorrectorsRaiseTheEpsSquaredOrder) {
  const std::string strang =
      "method S\nkind explicit\nsource test\nstages 3\norder 2\nc 0, 1/2, 1\nkick 0, 1, 0\n";
  Derived corrected = derive(spec_of(strang + "modified -1/24, 0, -1/24\n"));
  EXPECT_EQ(corrected.certificate.generalized.at(1), 3);
  Derived plain = derive(spec_of(strang + "modified -1/48, 0, -1/48\n"));
  EXPECT_EQ(plain.certificate.generalized.at(1), 2);
}

}  // namespace
}  // namespace erkn::gen
