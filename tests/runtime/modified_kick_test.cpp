// Modified kicks (Method::has_modified_kicks): the closed forms of Hess U v that the problems
// library gives every problem, the modified force G = grad(|grad U|^2) = 2 Hess U grad U the
// explicit stepper forms from them (or from the dense Hessian), its scale (a wrong one loses
// order), its statistics, and the refusals. The observed orders and symplecticity of these
// methods are checked with every other method's (order_test.cpp, symplecticity_test.cpp).
#include <gtest/gtest.h>

#include <string>

#include "problems.hpp"

namespace erkn::test {
namespace {

using Vec = Eigen::VectorXd;

std::vector<problems::Problem> every_problem() {
  return {problems::sine_gordon(8),   problems::sine_gordon(8, 3.0),
          problems::duffing(),        problems::stellar_orbits(),
          problems::fpu(3),           problems::henon_heiles(),
          problems::sine_gordon_2d(4)};
}

std::vector<Method> modified_kick_methods() {
  std::vector<Method> out;
  for (const Method& m : Method::all())
    if (m.has_modified_kicks()) out.push_back(m);
  return out;
}

double grad_norm2(const problems::Problem& p, const Vec& q) {
  Vec g(q.size());
  p.grad_u(q, g);
  return g.squaredNorm();
}

// max_i |G_i - d/dq_i |grad U|^2| / max |G|, the derivative by fourth-order central differences.
double mismatch_with_finite_differences(const problems::Problem& p, const Vec& q, const Vec& G) {
  const double e = 1e-3;
  Vec fd(q.size());
  for (Eigen::Index i = 0; i < q.size(); ++i) {
    auto at = [&](double k) {
      Vec x = q;
      x[i] += k * e;
      return grad_norm2(p, x);
    };
    fd[i] = (8 * (at(1) - at(-1)) - (at(2) - at(-2))) / (12 * e);
  }
  return (G - fd).cwiseAbs().maxCoeff() / G.cwiseAbs().maxCoeff();
}

Vec modified_force(const problems::Problem& p, const Vec& q) {
  Vec g(q.size()), hv(q.size());
  p.grad_u(q, g);
  p.hessian_vector_u(q, g, hv);
  return 2 * hv;
}

// Negative control: G off by 1e-4 (relative) fails the check the closed form passes.
TEST(ModifiedForce, ClosedFormOfEveryProblemIsTheGradientOfTheSquaredGradientNorm) {
  for (const problems::Problem& p : every_problem()) {
    SCOPED_TRACE(p.title);
    ASSERT_TRUE(p.hessian_vector_u);
    const Vec q = p.q0 + 0.3 * random_vector(p.dim(), 7);
    const Vec G = modified_force(p, q);
    EXPECT_LT(mismatch_with_finite_differences(p, q, G), 1e-8);
    EXPECT_GT(mismatch_with_finite_differences(p, q, (1 + 1e-4) * G), 3e-5);
    // Hess U v for any v: the directional derivative of grad U.
    const Vec v = random_vector(p.dim(), 11);
    Vec hv(q.size()), gp(q.size()), gm(q.size());
    p.hessian_vector_u(q, v, hv);
    p.grad_u(q + 1e-5 * v, gp), p.grad_u(q - 1e-5 * v, gm);
    EXPECT_LT((hv - (gp - gm) / 2e-5).cwiseAbs().maxCoeff(), 1e-7 * (1 + hv.cwiseAbs().maxCoeff()));
  }
}

// The explicit stepper's G: from hessian_vector_product and from the dense Hessian alike (the
// same trajectory), one product per modified kick that is evaluated.
TEST(ModifiedKicks, HessianVectorProductAndDenseHessianGiveTheSameStepsAndAreCounted) {
  const problems::Problem p = problems::henon_heiles();
  for (const Method& m : modified_kick_methods()) {
    SCOPED_TRACE(std::string(m.name()));
    System product = problems::system(p), dense = product;
    product.hessian = nullptr;
    dense.hessian_vector_product = nullptr;
    Integrator a(m, product, 0.1, p.q0, p.p0), b(m, dense, 0.1, p.q0, p.p0);
    a.step(20), b.step(20);
    EXPECT_LT((a.q() - b.q()).norm() + (a.p() - b.p()).norm(), 1e-13);
    const Statistics& s = a.statistics();
    long modified_stages = 0;
    for (double e : m.modified()) modified_stages += e != 0;
    // (FSAL: the first kick reuses the last one's force after the first step.)
    const bool fsal = m.table().c[0] == 0 && m.table().c[m.stages() - 1] == 1;
    const long reused = fsal && m.modified()[0] != 0 ? 19 : 0;
    // (A processed method's processor, pi^-1 at the start and pi for q(), has its own.)
    long processor_modified = 0;
    for (int k = 0; k < m.table().npre; ++k) processor_modified += m.table().pre_modified[k] != 0;
    EXPECT_EQ(s.hessian_vector_products,
              20 * modified_stages - reused + s.processor_applications * processor_modified);
    EXPECT_EQ(s.hessian_evaluations, 0);
    EXPECT_EQ(b.statistics().hessian_evaluations, b.statistics().hessian_vector_products);
    EXPECT_GT(s.hessian_vector_products, 0);
  }
}

// The scale of G is the generator's (methods.spec: p -= h (d_i grad U + h^2 e_i G)): G doubled
// (a Hessian-vector product without the factor 2 taken as G, the usual slip) loses the order of
// every method whose certified order the modified kicks carry.
TEST(ModifiedKicks, AWrongScaleOfTheModifiedForceLosesTheCertifiedOrder) {
  const problems::Problem p = problems::henon_heiles();
  const double T = 2.0;
  System wrong = problems::system(p);
  wrong.hessian = nullptr;
  wrong.hessian_vector_product = [hv = p.hessian_vector_u](const Vec& q, const Vec& v, Vec& out) {
    hv(q, v, out);
    out *= 2;
  };
  for (const Method& m : modified_kick_methods()) {
    if (m.order() <= 2) continue;  // (SABAC1: e enters its generalized order only)
    SCOPED_TRACE(std::string(m.name()));
    auto error_at = [&](const System& s, long n) {
      Integrator fine(m, problems::system(p), T / double(4 * n), p.q0, p.p0);
      Integrator run(m, s, T / double(n), p.q0, p.p0);
      fine.integrate(T), run.integrate(T);
      return (run.q() - fine.q()).norm();
    };
    const std::vector<long> n = {8, 11, 16, 23};
    std::vector<double> right, doubled;
    for (long k : n)
      right.push_back(error_at(problems::system(p), k)), doubled.push_back(error_at(wrong, k));
    EXPECT_LT(fitted_slope(n, doubled), m.order() - 0.5);
    EXPECT_GT(fitted_slope(n, right), m.order() - 0.5);  // (control: the right G keeps it)
  }
}

// The registry loop (symplecticity_test.cpp) checks these methods' one-step maps; its negative
// control for modified kicks: a "G" that is no gradient (2 (Hess U + S) grad U, S skew) makes the
// kick, and so the map, non-symplectic.
TEST(ModifiedKicks, AModifiedForceThatIsNoGradientBreaksSymplecticity) {
  Eigen::VectorXd y(6);
  y << 0.6, -0.4, 0.3, 0.2, 0.5, -0.7;
  System right = polynomial_system(), skewed = right;
  right.hessian_vector_product = [h = right.hessian](const Vec& q, const Vec& v, Vec& hv) {
    Eigen::MatrixXd H(3, 3);
    h(q, H);
    hv = H * v;
  };
  skewed.hessian = nullptr;
  skewed.hessian_vector_product = [r = right.hessian_vector_product](const Vec& q, const Vec& v,
                                                                     Vec& hv) {
    r(q, v, hv);
    hv += 0.3 * Eigen::Vector3d(v[1], -v[0], 0);
  };
  for (const Method& m : modified_kick_methods()) {
    SCOPED_TRACE(std::string(m.name()));
    EXPECT_LE(symplecticity_defect(m, right, 0.2, y), 1e-9);
    EXPECT_GE(symplecticity_defect(m, skewed, 0.2, y), 1e-6);
  }
}

System gradient_only(const problems::Problem& p) {
  System s = problems::system(p);
  s.hessian = nullptr;
  s.hessian_vector_product = nullptr;
  return s;
}

TEST(ModifiedKicks, ASystemWithoutTheModifiedForceIsRefusedNamingWhatIsMissing) {
  const problems::Problem p = problems::stellar_orbits();
  for (const Method& m : modified_kick_methods()) {
    SCOPED_TRACE(std::string(m.name()));
    try {
      Integrator run(m, gradient_only(p), 0.1, p.q0, p.p0);
      ADD_FAILURE() << "not refused";
    } catch (const Error& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("hessian_vector_product"), std::string::npos) << what;
      EXPECT_NE(what.find(std::string(m.name())), std::string::npos) << what;
      EXPECT_NE(what.find("Strang"), std::string::npos) << what;  // (the plain ones are named)
    }
  }
  // Control: the methods with plain kicks need neither.
  for (const Method& m : Method::all())
    if (m.is_explicit() && !m.has_modified_kicks())
      EXPECT_NO_THROW(Integrator(m, gradient_only(p), 0.1, p.q0, p.p0)) << m.name();
}

// A bad product fails the step like a bad gradient: named, the state kept.
TEST(ModifiedKicks, ABadHessianVectorProductFailsTheStepAndKeepsTheState) {
  const problems::Problem p = problems::stellar_orbits();
  const Method m = modified_kick_methods().front();
  for (bool wrong_size : {true, false}) {
    System s = gradient_only(p);
    bool fail = false;
    s.hessian_vector_product = [&fail, wrong_size](const Vec& q, const Vec&, Vec& out) {
      out = Vec::Zero(q.size());
      if (fail) out = wrong_size ? Vec::Zero(q.size() + 1) : Vec::Constant(q.size(), NAN);
    };
    Integrator run(m, s, 0.1, p.q0, p.p0);
    run.step();
    fail = true;
    const Vec q = run.q(), pp = run.p();
    try {
      run.step(5);
      ADD_FAILURE() << "not refused";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("hessian_vector_product callback"), std::string::npos)
          << e.what();
    }
    EXPECT_EQ(run.q(), q);
    EXPECT_EQ(run.p(), pp);
  }
}

}  // namespace
}  // namespace erkn::test
