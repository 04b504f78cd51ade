// Methods with entire coefficients (Method::entire(): the RKN limits, the explicit and the
// pole-free methods) accept any step size; only a method with poles refuses h^2 lambda beyond
// kPoleSearchMax, where its poles are not known. At large v their coefficients stay accurate:
// the symplectic conditions (Theorem 2, eq. (g)) hold in long double to the rounding of the
// phase, and with U = 0 a step is still exact.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <string_view>

#include "problems.hpp"

namespace erkn::test {
namespace {

// True when the closed form divides by something in v: a '/' followed by phi, v or a bracket
// holding either (a '/' between numbers, like 25/52, is a rational constant).
bool divides_by_v(std::string_view form) {
  for (size_t k = form.find('/'); k != std::string_view::npos; k = form.find('/', k + 1)) {
    if (k + 1 < form.size() && form[k + 1] != '(') {
      if (!std::isdigit(static_cast<unsigned char>(form[k + 1]))) return true;
      continue;
    }
    int depth = 0;
    size_t end = k + 1;
    for (; end < form.size(); ++end) {
      depth += form[end] == '(' ? 1 : form[end] == ')' ? -1 : 0;
      if (depth == 0) break;
    }
    const std::string_view group = form.substr(k + 1, end - k);
    if (group.find('v') != std::string_view::npos || group.find("phi") != std::string_view::npos)
      return true;
  }
  return false;
}

bool any_form_divides_by_v(const Method& m) {
  for (int k = 0; k < m.num_coefficients(); ++k)
    if (divides_by_v(m.table().closed_forms[k])) return true;
  return false;
}

TEST(LargeStep, EntireMeansNoPoleAndNoDenominatorInV) {
  int entire = 0, with_poles = 0;
  for (const Method& m : Method::all()) {
    if (m.kind() == Kind::rkn) continue;
    SCOPED_TRACE(std::string(m.name()));
    EXPECT_EQ(m.entire(), !any_form_divides_by_v(m));
    EXPECT_EQ(m.entire(), m.poles().empty());
    if (m.is_explicit()) EXPECT_TRUE(m.entire());
    (m.entire() ? entire : with_poles)++;
  }
  EXPECT_GT(entire, 0);
  EXPECT_GT(with_poles, 0);  // (the negative control: the paper's methods with poles)
  EXPECT_TRUE(divides_by_v("(1)/((1)*v^(1)*phi(0,v))"));  // (the detector itself)
  EXPECT_FALSE(divides_by_v("(25/52)*phi(0,(16/25)*v)"));
}

// The symplectic conditions of Theorem 2 at v, in long double, from the stored c_i, d_i: the
// largest residual relative to the rounding of the phase sqrt(v) (eps sqrt(v)), with b and bbar
// evaluated at v_b (v itself, or a perturbed v: the negative control).
long double symplectic_residual(const Method& m, double v, double v_b) {
  using LD = long double;
  const Coefficients k = m.at(v), kb = m.at(v_b);
  const LD x = std::sqrt(LD(v));
  auto phi0 = [&](LD c) { return std::cos(c * x); };
  auto phi1 = [&](LD c) { return c * x == 0 ? LD(1) : std::sin(c * x) / (c * x); };
  LD worst = 0;
  for (int i = 0; i < m.stages(); ++i) {
    const LD c = m.table().c[i], d = m.table().d[i], b = kb.b[i], bbar = kb.bbar[i];
    worst = std::max(worst, std::abs(phi0(1) * b + x * x * phi1(1) * bbar - d * phi0(c)));
    worst = std::max(worst, std::abs(phi1(1) * b - phi0(1) * bbar - c * d * phi1(c)));
    for (int j = 0; j < i; ++j)
      worst =
          std::max(worst, std::abs(LD(kb.bbar[j]) * b - bbar * LD(kb.b[j]) - d * LD(k.abar(i, j))));
  }
  return worst / (std::numeric_limits<double>::epsilon() * x);
}

TEST(LargeStep, CoefficientsOfEntireMethodsStayAccurateAtLargeV) {
  for (const Method& m : Method::all()) {
    if (m.kind() == Kind::rkn || !m.entire()) continue;
    SCOPED_TRACE(std::string(m.name()));
    for (double v : {1e5, 1e8, 1e11}) {
      SCOPED_TRACE(v);
      EXPECT_LT(symplectic_residual(m, v, v), 64);
      EXPECT_GT(symplectic_residual(m, v, v * (1 + 1e-9)), 1e3);  // (negative control)
    }
  }
}

System free_system(const Eigen::VectorXd& lambda) {
  System s;
  s.M = Stiffness::diagonal(lambda);
  s.gradient = [](const Eigen::VectorXd&, Eigen::VectorXd& g) { g.setZero(); };
  s.hessian_vector_product = [](const Eigen::VectorXd&, const Eigen::VectorXd& v,
                                Eigen::VectorXd& hv) { hv.setZero(v.size()); };
  return s;
}

// h^2 lambda_max = 1e8, far beyond kPoleSearchMax: entire methods step, exactly for U = 0 (to
// the rounding of the phase, n eps w h per step); methods with poles refuse it by name.
TEST(LargeStep, EntireMethodsAcceptAnyStepSizeAndStayExactForFreeMotion) {
  const Eigen::Vector3d lambda(0.25, 3.0, 1e6), q0(0.6, -0.4, 0.3), p0(0.2, 0.5, -0.7);
  const double h = 10;
  const int n = 5;
  ASSERT_GT(h * h * lambda.maxCoeff(), 100 * generated::kPoleSearchMax);
  for (const Method& m : Method::all()) {
    SCOPED_TRACE(std::string(m.name()));
    if (!m.entire()) {
      try {
        Integrator(m, free_system(lambda), h, q0, p0);
        ADD_FAILURE() << "accepted h^2 lambda beyond the range of known poles";
      } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("poles are known"), std::string::npos) << e.what();
      }
      continue;
    }
    Integrator run(m, free_system(lambda), h, q0, p0);
    run.integrate(n * h);
    if (m.kind() == Kind::rkn) continue;  // (accepted; not exact: the V -> 0 limit)
    for (int e = 0; e < 3; ++e) {
      using LD = long double;
      const LD w = std::sqrt(LD(lambda[e])), t = n * h;
      const LD q = std::cos(w * t) * q0[e] + std::sin(w * t) / w * p0[e];
      EXPECT_NEAR(run.q()[e], double(q), 64 * n * 2.2e-16 * double(w * h) * 1.0) << e;
    }
    const StepSizeAdvice advice = advise_step_size(m, run.system(), h, q0, p0);
    for (const AdvisorFinding& f : advice.findings) EXPECT_NE(f.hazard, Hazard::pole);
  }
}

}  // namespace
}  // namespace erkn::test
