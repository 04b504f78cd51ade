// The problems library's potentials with a compiled gradient and Hessian-vector product
// (problems::Potential::compiled_grad_u, the Python module's built-ins): an Integrator given it
// steps every explicit method with that functor inlined at d <= 4 and in a half-spectrum basis
// (circulant M) and gives grad_u's and hessian_vector_u's states bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <erkn/compiled_gradient.hpp>  // (detail::kFixedMaxD)
#include <erkn/erkn.hpp>
#include <erkn/problems.hpp>
#include <string>
#include <utility>
#include <vector>

namespace erkn::test {
namespace {

struct Outcome {
  Eigen::VectorXd q, p, observed;
  Statistics stats;
};

/// 60 steps with output every 7 and a shorter last step: q, p at the end and what the observer
/// saw.
Outcome run(Integrator integrator) {
  Outcome r;
  std::vector<double> seen;
  integrator.integrate(
      3.01,
      [&](double, const Eigen::VectorXd& q, const Eigen::VectorXd& p) {
        seen.insert(seen.end(), q.begin(), q.end()), seen.insert(seen.end(), p.begin(), p.end());
      },
      7);
  r.q = integrator.q(), r.p = integrator.p(), r.stats = integrator.statistics();
  r.observed = Eigen::Map<Eigen::VectorXd>(seen.data(), Eigen::Index(seen.size()));
  return r;
}

bool identical(const Outcome& a, const Outcome& b) {
  return a.q == b.q && a.p == b.p && a.observed == b.observed &&
         a.stats.gradient_evaluations == b.stats.gradient_evaluations &&
         a.stats.hessian_vector_products == b.stats.hessian_vector_products &&
         a.stats.steps == b.stats.steps;
}

/// The run of u (its grad_u as System::gradient) with M, from a state where every potential's
/// gradient is far from linear; with `compiled`, the Integrator also gets those steppers.
Outcome run_of(const Method& m, const problems::Potential& u, const Stiffness& M, Eigen::Index d,
               std::shared_ptr<const detail::CompiledSteppers> compiled) {
  const Eigen::VectorXd q0 = Eigen::VectorXd::LinSpaced(d, 0.4, 1.3);
  const Eigen::VectorXd p0 = Eigen::VectorXd::LinSpaced(d, 1.0, -0.5);
  return run(Integrator(m, problems::system(M, u), 0.05, q0, p0, {}, 0, std::move(compiled)));
}

struct Named {
  std::string name;
  problems::Potential u, perturbed;  // (perturbed: a parameter moved by 2^-40 relative)
};

std::vector<Named> potentials() {
  const double moved = 1 + std::ldexp(1.0, -40);
  return {{"sine", problems::sine_potential(), problems::sine_potential(moved)},
          {"sine, kappa 0.7", problems::sine_potential(0.7), problems::sine_potential(0.7 * moved)},
          {"duffing", problems::duffing_potential(0.5), problems::duffing_potential(0.5 * moved)},
          {"quartic", problems::quartic_potential(2), problems::quartic_potential(2 * moved)}};
}

/// The compiled steppers' scenes: d = 1..4 with scalar and diagonal M (a fixed dimension), and
/// circulant M at d = 16 (the half-spectrum basis).
std::vector<std::pair<Eigen::Index, Stiffness>> scenes() {
  std::vector<std::pair<Eigen::Index, Stiffness>> out;
  for (Eigen::Index d = 1; d <= detail::kFixedMaxD; ++d) {
    out.emplace_back(d, Stiffness::scalar(9));
    out.emplace_back(d, Stiffness::diagonal(Eigen::VectorXd::LinSpaced(d, 4, 16)));
  }
  Eigen::VectorXd column = Eigen::VectorXd::Zero(16);
  column[0] = 41, column[1] = column[15] = -16;  // (a mass term of 9)
  out.emplace_back(16, Stiffness::circulant(column));
  return out;
}

std::string label(const Named& p, const Method& m, Eigen::Index d, const Stiffness& M) {
  return p.name + ", " + std::string(m.name()) + ", d = " + std::to_string(d) + ", structure " +
         std::to_string(int(M.structure()));
}

TEST(CompiledPotentials, EveryExplicitMethodGivesTheCallbackStatesAndUsesTheCompiledGradient) {
  int cases = 0;
  for (const Named& p : potentials()) {
    ASSERT_TRUE(p.u.compiled_grad_u) << p.name;
    for (const Method& m : Method::all()) {
      if (!m.is_explicit()) continue;
      for (const auto& [d, M] : scenes()) {
        SCOPED_TRACE(label(p, m, d, M));
        const Outcome callback = run_of(m, p.u, M, d, nullptr);
        EXPECT_TRUE(identical(run_of(m, p.u, M, d, p.u.compiled_grad_u), callback));
        // Negative control: the steps call the compiled functor (System::gradient is u's, the
        // compiled one another parameter's) and the comparison sees a 2^-40 change.
        EXPECT_FALSE(identical(run_of(m, p.u, M, d, p.perturbed.compiled_grad_u), callback));
        ++cases;
      }
    }
  }
  EXPECT_GE(cases, 4 * 20 * 9);
}

TEST(CompiledPotentials, ModifiedKicksCallTheCompiledHessianVectorProduct) {
  int cases = 0;
  for (const Named& p : potentials())
    for (const Method& m : Method::all()) {
      if (!m.is_explicit() || !m.has_modified_kicks()) continue;
      for (const auto& [d, M] : scenes()) {
        SCOPED_TRACE(label(p, m, d, M));
        // System's product is moved by 2^-20 (the modified force is h^2 e_i G: a 2^-40 change
        // of it can round away); the compiled steps do not call it.
        problems::Potential mixed = p.u;
        mixed.hessian_vector_u = [hv = p.u.hessian_vector_u](const Eigen::VectorXd& q,
                                                             const Eigen::VectorXd& v,
                                                             Eigen::VectorXd& out) {
          hv(q, v, out);
          out *= 1 + 0x1p-20;
        };
        const Outcome callback = run_of(m, p.u, M, d, nullptr);
        const Outcome compiled = run_of(m, mixed, M, d, p.u.compiled_grad_u);
        EXPECT_TRUE(identical(compiled, callback));
        EXPECT_GT(compiled.stats.hessian_vector_products, 0);
        // Negative control: through System's callbacks the other product is seen.
        EXPECT_FALSE(identical(run_of(m, mixed, M, d, nullptr), callback));
        ++cases;
      }
    }
  EXPECT_GE(cases, 4 * 8 * 9);
}

}  // namespace
}  // namespace erkn::test
