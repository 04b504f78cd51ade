// Methods a program adds (Method::add, Method::load) and the numeric order check they pass.
// Its own executable: the methods it adds must not join the registry loops of the other tests.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <deque>
#include <fstream>
#include <string>
#include <vector>

#include "erkn/erkn.hpp"
#include "erkn/problems.hpp"
#include "order_conditions.hpp"
#include "refusals.hpp"

namespace erkn {
namespace {

std::vector<long double> as_long(const double* x, int s) { return {x, x + s}; }

using test::error_of;

// The numeric check reproduces the generator's certified orders for every explicit method with
// plain kicks (it has no modified-kick term: Method::load refuses modified kicks).
TEST(OrderConditions, ReproduceTheCertifiedOrdersOfEveryExplicitMethod) {
  int checked = 0;
  for (const Method& m : Method::all()) {
    if (!m.is_explicit() || m.kind() != Kind::erkn || m.has_modified_kicks() || m.is_processed())
      continue;  // (a processed method's order is psi's, its table the kernel's)
    const auto c = as_long(m.table().c, m.stages()), d = as_long(m.table().d, m.stages());
    const auto g = m.generalized_order();
    const auto r = detail::check_order(c, d, m.order(), g, 64 * DBL_EPSILON);
    EXPECT_EQ(r.order, m.order()) << m.name();
    EXPECT_EQ(r.failure, "") << m.name();
    for (size_t K = 0; K < g.size(); ++K)
      EXPECT_EQ(r.generalized[K], g[K]) << m.name() << " K " << K + 1;
    // Negative controls: c_1 moved by 1e-9 loses the order; so does d_1 (sum d_i = 1 fails).
    auto c2 = c;
    c2[0] += 1e-9L;
    const auto r2 = detail::check_order(c2, d, m.order(), g, 64 * DBL_EPSILON);
    EXPECT_LT(r2.order, m.order()) << m.name();
    EXPECT_NE(r2.failure.find("tree ["), std::string::npos) << m.name();
    auto d2 = d;
    d2[0] *= 1 + 1e-9L;
    EXPECT_EQ(detail::check_order(c, d2, m.order(), g, 64 * DBL_EPSILON).order, 0) << m.name();
    ++checked;
  }
  EXPECT_GE(checked, 11);
}

// A loaded method's error constants come from the residuals the check computes: over the V^0
// special Nystrom conditions, a part of the generator's norm (which also counts the M^j F(tau)
// and the q-error conditions), so never above it; measured 0.66-1.00 of it (the printout).
TEST(OrderConditions, ErrorConstantsAreTheV0PartOfTheGenerators) {
  int checked = 0;
  for (const Method& m : Method::all()) {
    if (!m.is_explicit() || m.kind() != Kind::erkn || m.has_modified_kicks() || m.is_processed() ||
        std::isnan(m.error_constant()))
      continue;
    const auto c = as_long(m.table().c, m.stages()), d = as_long(m.table().d, m.stages());
    const auto g = m.generalized_order();
    const auto r = detail::check_order(c, d, m.order(), g, 64 * DBL_EPSILON);
    std::printf("%-12s V^0 part %.4g generator %.4g ratio %.3f\n", std::string(m.name()).c_str(),
                r.error_constant, m.error_constant(), r.error_constant / m.error_constant());
    EXPECT_GT(r.error_constant, 0.5 * m.error_constant()) << m.name();
    EXPECT_LE(r.error_constant, m.error_constant() * (1 + 1e-5)) << m.name();
    for (size_t K = 0; K < g.size(); ++K)  // NaN at g_K = kMaxTreeOrder: no trees beyond
      if (g[K] < detail::kMaxTreeOrder)
        EXPECT_LE(r.generalized_error_constant[K], m.generalized_error_constant()[K] * (1 + 1e-5))
            << m.name() << " K " << K + 1;
    // Negative control: with c_1 moved by 1e-9 the order drops and the norm, now taken at the
    // failing lower power, is the size of the perturbation, not the method's constant.
    auto c2 = c;
    c2[0] += 1e-9L;
    const auto r2 = detail::check_order(c2, d, m.order(), g, 64 * DBL_EPSILON);
    EXPECT_LT(r2.error_constant, 1e-6) << m.name();
    ++checked;
  }
  EXPECT_GE(checked, 11);
}

// A long decimal of a registry constant ("1/2" or a >= 45-digit decimal); "" for others.
std::string decimal(const std::string& exact) {
  char buf[64];
  if (auto slash = exact.find('/'); slash != std::string::npos) {
    if (exact.find_first_not_of("0123456789/-") != std::string::npos) return "";
    std::snprintf(buf, sizeof buf, "%.25Lg",
                  std::stold(exact.substr(0, slash)) / std::stold(exact.substr(slash + 1)));
    return buf;
  }
  if (exact.find_first_not_of("0123456789.-e") != std::string::npos) return "";
  return exact;
}

// A method file for registry method m under `name`, or "" when m's constants are not decimals.
std::string method_json(const Method& m, const std::string& name, const std::string& extra = "") {
  std::string c, d, g;
  for (int i = 0; i < m.stages(); ++i) {
    const std::string ci = decimal(m.table().c_exact[i]), di = decimal(m.table().d_exact[i]);
    if (ci.empty() || di.empty()) return "";
    c += (i ? ", " : "") + ci, d += (i ? ", " : "") + di;
  }
  for (int x : m.generalized_order()) g += (g.empty() ? "" : ", ") + std::to_string(x);
  return "{\"methods\": [{\"name\": \"" + name +
         "\", \"kind\": \"explicit\", \"stages\": " + std::to_string(m.stages()) +
         ", \"order\": " + std::to_string(m.order()) + ", \"generalized_order\": [" + g +
         "], \"c\": [" + c + "], \"d\": [" + d + "]" + extra + "}]}\n";
}

std::string write_file(const std::string& name, const std::string& text) {
  const std::string path = testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

System duffing() {
  System s;
  s.M = Stiffness::scalar(100.0);
  s.gradient = [](const Eigen::VectorXd& q, Eigen::VectorXd& g) {
    g = 0.0009 * (q - 2 * q.cwiseProduct(q).cwiseProduct(q));
  };
  s.potential = [](const Eigen::VectorXd& q) {
    return 0.0009 * (0.5 * q.squaredNorm() - 0.5 * q.array().pow(4).sum());
  };
  return s;
}

// Loaded from data, a registry method integrates bit-identically to the compiled one.
TEST(MethodLoad, LoadedExplicitMethodsIntegrateBitIdenticallyToTheCompiledOnes) {
  int loaded = 0;
  for (size_t k = 0; k < Method::all().size(); ++k) {
    const Method m = Method::all()[k];
    if (!m.is_explicit() || m.kind() != Kind::erkn || m.has_modified_kicks() || m.is_processed() ||
        m.name().ends_with("_data"))
      continue;  // (modified kicks and processors do not load from data)
    const std::string json = method_json(m, std::string(m.name()) + "_data");
    if (json.empty()) continue;
    const auto added = Method::load(write_file(std::string(m.id_name()) + ".json", json));
    ASSERT_EQ(added.size(), 1u);
    EXPECT_EQ(&Method::by_name(std::string(m.name()) + "_data"), &Method::all().back());
    Eigen::VectorXd q0(1), p0(1);
    q0 << 0.0;
    p0 << 10.0;
    Integrator a(m, duffing(), 0.01, q0, p0), b(added[0], duffing(), 0.01, q0, p0);
    a.integrate(1.0), b.integrate(1.0);
    EXPECT_EQ(a.q()[0], b.q()[0]) << m.name();
    EXPECT_EQ(a.p()[0], b.p()[0]) << m.name();
    EXPECT_LE(added[0].error_constant(), m.error_constant() * (1 + 1e-5)) << m.name();
    EXPECT_GT(added[0].error_constant(), 0.5 * m.error_constant()) << m.name();
    for (double v : {0.0, 0.3, 7.0}) {  // and its coefficients are the compiled ones
      const Coefficients x = m.at(v), y = added[0].at(v);
      for (int i = 0; i < m.stages(); ++i) EXPECT_NEAR(x.b[i], y.b[i], 1e-14) << m.name();
    }
    ++loaded;
  }
  EXPECT_GE(loaded, 6);
}

TEST(MethodLoad, ChangedDigitIsRefusedNamingTheConditionAndAddsNothing) {
  const Method& m = Method::by_name("Yoshida4");
  std::string json = method_json(m, "Yoshida4_changed");
  const size_t at = json.find("\"d\": [") + 12;  // the 5th digit of d_1
  json[at] = json[at] == '9' ? '8' : char(json[at] + 1);
  const size_t before = Method::all().size();
  const std::string e = error_of([&] { Method::load(write_file("changed.json", json)); });
  EXPECT_NE(e.find("Yoshida4_changed"), std::string::npos) << e;
  EXPECT_NE(e.find("claims order 4"), std::string::npos) << e;
  EXPECT_NE(e.find("tree ["), std::string::npos) << e;
  EXPECT_EQ(Method::all().size(), before);
  EXPECT_THROW(Method::by_name("Yoshida4_changed"), Error);
}

TEST(MethodLoad, RefusesModifiedKicksImplicitKindsDuplicatesAndMalformedFiles) {
  const Method& m = Method::by_name("Yoshida4");
  const size_t before = Method::all().size();
  const auto refusal = [&](const std::string& json) {
    return error_of([&] { Method::load(write_file("refused.json", json)); });
  };
  EXPECT_NE(
      refusal(method_json(m, "Y_mod", ", \"modified\": [0, -0.01, 0]")).find("modified kicks"),
      std::string::npos);
  std::string implicit = method_json(m, "Y_impl");
  implicit.replace(implicit.find("explicit"), 8, "erkn");
  EXPECT_NE(refusal(implicit).find("only explicit methods"), std::string::npos);
  EXPECT_NE(refusal(method_json(m, "Yoshida4")).find("already listed"), std::string::npos);
  EXPECT_NE(refusal("{\"methods\": [").find("malformed JSON"), std::string::npos);
  EXPECT_NE(error_of([] { Method::load("/nonexistent/m.json"); }).find("cannot read"),
            std::string::npos);
  EXPECT_EQ(Method::all().size(), before);
}

// Two steps of h / 2 of an implicit ERKN method as one step of h: a method of 2s stages whose
// coefficients at v = h^2 lambda follow from the base method's at u = v / 4 and the exact linear
// flow (the half step's flow composes with the second half's: nodes c / 2 and (1 + c) / 2).
// With u = v / 4, phi0(x) = cos sqrt(x), phi1(x) = sin sqrt(x) / sqrt(x):
//   abar'_ij = abar_ij / 4 within each half; second half row i, first half j:
//     (phi0(c_i^2 u) bbar_j + c_i phi1(c_i^2 u) b_j) / 4 (the first half's increments carried
//     over c_i h by the flow);
//   bbar'_j = (phi0(u) bbar_j + phi1(u) b_j) / 4,  b'_j = (phi0(u) b_j - u phi1(u) bbar_j) / 2;
//   second half: bbar'_(s+j) = bbar_j / 4, b'_(s+j) = b_j / 2.
// kCoupled = false drops the c_i phi1 b_j term (the negative control).
const Method* composed_base = nullptr;  // (a table's coefficients are a plain function pointer)

double phi0(double x) { return std::cos(std::sqrt(x)); }
double phi1(double x) { return x == 0 ? 1.0 : std::sin(std::sqrt(x)) / std::sqrt(x); }

template <bool kCoupled>
void composed_coefficients(double v, double* b2, double* bbar2, double* abar2) {
  const Method& m = *composed_base;
  const int s = m.stages();
  const double u = v / 4;
  std::array<double, kMaxStages> b{}, bbar{};
  std::array<double, Coefficients::kMaxPacked> abar{};
  m.evaluate(u, b.data(), bbar.data(), abar.data());
  for (int i = 0; i < s; ++i) {
    const double c = m.table().c[i], f0 = phi0(c * c * u), f1 = kCoupled ? c * phi1(c * c * u) : 0;
    for (int j = 0; j <= i; ++j) {
      abar2[Coefficients::packed(i, j)] = abar[Coefficients::packed(i, j)] / 4;
      abar2[Coefficients::packed(s + i, s + j)] = abar[Coefficients::packed(i, j)] / 4;
    }
    for (int j = 0; j < s; ++j)
      abar2[Coefficients::packed(s + i, j)] = (f0 * bbar[j] + f1 * b[j]) / 4;
    bbar2[i] = (phi0(u) * bbar[i] + phi1(u) * b[i]) / 4, bbar2[s + i] = bbar[i] / 4;
    b2[i] = (phi0(u) * b[i] - u * phi1(u) * bbar[i]) / 2, b2[s + i] = b[i] / 2;
  }
}

// The composed table of `base` (kept for the process: the registry holds its address).
const Method& add_composed(const Method& base, bool coupled) {
  struct Storage {
    generated::Table table;
    std::vector<double> c, d, poles;
    std::vector<std::string> forms;
    std::vector<const char*> form_ptrs;
    std::string name;
  };
  static std::deque<Storage> kept;
  Storage& x = kept.emplace_back(Storage{base.table(), {}, {}, {}, {}, {}, {}});
  const int s = base.stages();
  for (int half = 0; half < 2; ++half)
    for (int i = 0; i < s; ++i)
      x.c.push_back((half + base.table().c[i]) / 2), x.d.push_back(base.table().d[i] / 2);
  // Closed forms: only whether each abar'_ii is identically zero is read (as the base's abar_ii).
  const int S = 2 * s;  // (b, bbar, then abar packed: Method::num_coefficients)
  x.forms.assign(2 * S + S * (S + 1) / 2, "composed");
  for (int half = 0; half < 2; ++half)
    for (int i = 0; i < s; ++i)
      x.forms[2 * S + Coefficients::packed(half * s + i, half * s + i)] =
          base.table().closed_forms[2 * s + Coefficients::packed(i, i)];
  for (const std::string& f : x.forms) x.form_ptrs.push_back(f.c_str());
  for (double p : base.poles())
    if (4 * p <= generated::kPoleSearchMax) x.poles.push_back(4 * p);
  x.name = std::string(base.id_name()) + (coupled ? "_twice" : "_uncoupled");
  generated::Table& t = x.table;
  t.name = t.id = x.name.c_str();
  t.stages = 2 * s, t.c = x.c.data(), t.d = x.d.data(), t.paper = false;
  t.c_exact = t.d_exact = nullptr, t.series = nullptr, t.closed_forms = x.form_ptrs.data();
  t.poles = x.poles.data(), t.npoles = int(x.poles.size());
  t.coefficients = coupled ? composed_coefficients<true> : composed_coefficients<false>;
  return Method::add(t);
}

// Every implicit ERKN method of the registry, composed with itself (2s stages: 4 to 8, beyond
// the 4 the fixed-dimension steppers unroll, which then loop over the stages), integrates as the
// method itself at half the step and twice the steps (P3, d = 2: a fixed-dimension stepper).
TEST(MethodAdd, ComposedImplicitMethodsIntegrateAsTheirHalfSteps) {
  const problems::Problem P = problems::stellar_orbits();
  const System sys = problems::system(P);
  const double h = 1.0 / 20;
  const long n = 100;
  std::vector<const Method*> bases;
  for (const Method& m : Method::all())
    if (m.kind() == Kind::erkn && !m.is_explicit() && 2 * m.stages() <= kMaxStages)
      bases.push_back(&m);
  ASSERT_FALSE(bases.empty());
  for (const Method* base : bases) {
    composed_base = base;
    Integrator half(*base, sys, h / 2, P.q0, P.p0);
    half.integrate(h * double(n));
    for (bool coupled : {true, false}) {
      const Method& twice = add_composed(*base, coupled);
      Integrator whole(twice, sys, h, P.q0, P.p0);
      whole.integrate(h * double(n));
      EXPECT_EQ(whole.statistics().steps, n);
      const double diff = std::max((whole.q() - half.q()).norm(), (whole.p() - half.p()).norm());
      if (coupled)
        EXPECT_LT(diff, 1e-12) << twice.name();
      else  // (negative control: the first half's increments not carried into the second's
            // stages; ~1.3e-9 here, the composed methods <= 4e-14)
        EXPECT_GT(diff, 1e-10) << twice.name();
    }
  }
}

TEST(MethodAdd, AddedTablesJoinTheRegistryAndBadOnesAreRefused) {
  generated::Table t = Method::by_name("Strang").table();
  t.name = "MyStrang", t.id = "MyStrang";
  const size_t before = Method::all().size();
  const Method& added = Method::add(t);
  EXPECT_EQ(&Method::by_name("MyStrang"), &added);
  EXPECT_EQ(&Method::get(added.id()), &added);
  EXPECT_EQ(Method::all().size(), before + 1);
  EXPECT_NE(error_of([&] { Method::add(t); }).find("already listed"), std::string::npos);
  generated::Table big = t;
  big.name = big.id = "Big", big.stages = kMaxStages + 1;
  EXPECT_NE(error_of([&] { Method::add(big); }).find("stages"), std::string::npos);
  generated::Table formless = t;  // (the steppers read abar_ii's zeros from the closed forms)
  formless.name = formless.id = "Formless", formless.closed_forms = nullptr;
  EXPECT_NE(error_of([&] { Method::add(formless); }).find("closed forms"), std::string::npos);
  // Modified kicks on an implicit table (the explicit stepper alone kicks with them).
  generated::Table mod = Method::by_name("SERKN2s4").table();
  mod.name = mod.id = "Mod";
  const double e[] = {-1.0 / 72, -1.0 / 72};
  mod.modified = e;
  EXPECT_NE(error_of([&] { Method::add(mod); }).find("modified kicks"), std::string::npos);
  EXPECT_EQ(Method::all().size(), before + 1);
  mod.modified = nullptr;  // (negative control: without them it is addable)
  mod.name = mod.id = "ModPlain";
  EXPECT_NO_THROW(Method::add(mod));
}

}  // namespace
}  // namespace erkn
