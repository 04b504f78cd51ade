// The emitted double-precision coefficient functions (generated/src/tables.cpp: closed forms,
// switching to Taylor series where the closed form cancels) against an independent evaluation
// of the emitted closed-form strings in 60-digit arithmetic (GiNaC/CLN), over v in [0, 100].
#include <ginac/ginac.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "derive.hpp"
#include "erkn/method.hpp"
#include "phi.hpp"

namespace {

using erkn::Method;

constexpr double kTolerance = 1e-13;  // relative to max(1, |value|), issue 2 item 7

std::vector<double> sample_points() {
  std::vector<double> v;
  for (int e = -8; e <= -2; ++e)
    for (double m : {1.0, 2.0, 5.0}) v.push_back(m * std::pow(10.0, e));
  for (int i = 1; i <= 2000; ++i) v.push_back(0.05 * i);
  return v;
}

bool near_pole(const Method& m, double v) {
  double p = m.nearest_pole(v);
  return p > 0 && std::abs(v - p) < 1e-2 * p;
}

std::vector<double> emitted(const Method& m, double v) {
  const int s = m.stages();
  std::vector<double> b(s), bbar(s), abar(s * (s + 1) / 2);
  m.table().coefficients(v, b.data(), bbar.data(), abar.data());
  std::vector<double> all = b;
  all.insert(all.end(), bbar.begin(), bbar.end());
  all.insert(all.end(), abar.begin(), abar.end());
  return all;
}

struct Reference {
  GiNaC::symbol v{"v"};
  std::vector<GiNaC::ex> forms;
  explicit Reference(const Method& m) {
    GiNaC::parser read = erkn::gen::make_parser(v);
    for (int k = 0; k < m.num_coefficients(); ++k) forms.push_back(read(m.table().closed_forms[k]));
  }
  double at(int k, double x) const {
    GiNaC::Digits = 60;
    GiNaC::ex val = GiNaC::evalf(forms[k].subs(v == GiNaC::numeric(x)));
    return GiNaC::ex_to<GiNaC::numeric>(val).to_double();
  }
};

// Worst error of `values(v)` against the reference, scaled by max(1, |reference|).
struct Worst {
  double error = 0, v = 0;
  int index = -1;
};

template <class F>
Worst worst_error(const Method& m, const Reference& ref, F values) {
  Worst w;
  for (double v : sample_points()) {
    if (near_pole(m, v)) continue;
    std::vector<double> got = values(v);
    for (int k = 0; k < m.num_coefficients(); ++k) {
      double want = ref.at(k, v);
      double err = std::abs(got[k] - want) / std::max(1.0, std::abs(want));
      if (err > w.error) w = {err, v, k};
    }
  }
  return w;
}

TEST(CoefficientAccuracy, EmittedCodeMatchesHighPrecisionClosedForms) {
  for (const Method& m : Method::all()) {
    if (m.kind() != erkn::Kind::erkn) continue;
    Reference ref(m);
    Worst w = worst_error(m, ref, [&](double v) { return emitted(m, v); });
    EXPECT_LE(w.error, kTolerance) << m.name() << ": coefficient " << w.index << " at v = " << w.v;
    std::printf("%-12s worst error %.2e (coefficient %d, v = %g)\n", std::string(m.name()).c_str(),
                w.error, w.index, w.v);
  }
}

// Negative control: the same measurement flags a table wrong by a relative 1e-12.
TEST(CoefficientAccuracy, PerturbedCoefficientsAreDetected) {
  const Method& m = Method::by_name("SERKN3s4(1)");
  Reference ref(m);
  Worst w = worst_error(m, ref, [&](double v) {
    std::vector<double> c = emitted(m, v);
    c.back() *= 1 + 1e-12;
    return c;
  });
  EXPECT_GT(w.error, kTolerance);
}

TEST(CoefficientAccuracy, RknLimitsAreTheValuesAtZero) {
  for (const Method& m : Method::all()) {
    if (m.kind() != erkn::Kind::rkn) continue;
    std::vector<double> limit = emitted(m, 0.0), at_two = emitted(m, 2.0);
    // reference: "V -> 0 limit of NAME (...)"
    std::string ref(m.reference()), prefix = "limit of ";
    size_t from = ref.find(prefix) + prefix.size();
    const Method& erkn_twin = Method::by_name(ref.substr(from, ref.find(" (", from) - from));
    ASSERT_EQ(erkn_twin.kind(), erkn::Kind::erkn);
    std::vector<double> at_zero = emitted(erkn_twin, 0.0);
    for (size_t k = 0; k < limit.size(); ++k) {
      EXPECT_EQ(limit[k], at_two[k]) << m.name() << ": RKN coefficients must not depend on v";
      EXPECT_NEAR(limit[k], at_zero[k], 1e-15) << m.name() << " vs " << erkn_twin.name();
    }
  }
}

// Eq. (g), first two lines, evaluated on the emitted doubles: phi0(v) b_i + v phi1(v) bbar_i =
// d_i phi0(c_i^2 v) and phi1(v) b_i - phi0(v) bbar_i = c_i d_i phi1(c_i^2 v).
TEST(CoefficientAccuracy, EmittedValuesSatisfySymplecticConditions) {
  auto phi0 = [](double v) { return std::cos(std::sqrt(v)); };
  auto phi1 = [](double v) { return v == 0 ? 1.0 : std::sin(std::sqrt(v)) / std::sqrt(v); };
  for (const Method& m : Method::all()) {
    if (m.kind() != erkn::Kind::erkn) continue;
    for (double v : {0.0, 1e-6, 0.3, 2.0, 17.0, 90.0}) {
      if (near_pole(m, v)) continue;
      std::vector<double> k = emitted(m, v);
      for (int i = 0; i < m.stages(); ++i) {
        double b = k[i], bbar = k[m.stages() + i], c = m.table().c[i], d = m.table().d[i];
        EXPECT_NEAR(phi0(v) * b + v * phi1(v) * bbar, d * phi0(c * c * v), 1e-14 * (1 + v));
        EXPECT_NEAR(phi1(v) * b - phi0(v) * bbar, c * d * phi1(c * c * v), 1e-14 * (1 + v));
      }
    }
  }
}

// phi_j(v) + v phi_{j+2}(v) = 1/j!  and  phi0(v)^2 + v phi1(v)^2 = 1, in 60 digits.
TEST(PhiFunctions, IdentitiesHold) {
  GiNaC::Digits = 60;
  for (double x : {1e-9, 1e-3, 0.5, 0.99, 1.0, 3.0, 40.0, 250.0}) {
    GiNaC::numeric v(x);
    auto phi = [&](int j) {
      return GiNaC::ex_to<GiNaC::numeric>(GiNaC::evalf(erkn::gen::phi(j, v)));
    };
    for (int j = 0; j <= 4; ++j) {
      GiNaC::numeric lhs = phi(j) + v * phi(j + 2),
                     rhs = GiNaC::numeric(1) / GiNaC::factorial(GiNaC::numeric(j));
      EXPECT_LT(GiNaC::abs(lhs - rhs).to_double(), 1e-45) << "j = " << j << ", v = " << x;
    }
    EXPECT_LT(GiNaC::abs(phi(0) * phi(0) + v * phi(1) * phi(1) - 1).to_double(), 1e-45);
  }
}

}  // namespace
