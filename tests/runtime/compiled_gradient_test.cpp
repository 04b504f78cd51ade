// erkn::make_integrator (erkn/compiled_gradient.hpp): the gradient compiled into the explicit
// steppers of d <= 4 and of the half-spectrum bases (circulant M, periodic grids) gives the
// states, statistics and errors of System::gradient (one step template, one arithmetic), and is
// what those steppers call.
#include <gtest/gtest.h>

#include <cmath>
#include <erkn/compiled_gradient.hpp>
#include <erkn/erkn.hpp>
#include <string>
#include <type_traits>

namespace erkn::test {
namespace {

/// grad U of U = sum_i (q_i^4/4 - k q_i^2/2) + eps sum_i q_i^2 q_{i+1} (cyclic), counting its
/// calls from the compiled steps (on fixed-size vectors, or on maps in a half-spectrum basis) in
/// *compiled_calls; scale multiplies the quartic term (1: the gradient itself; else a negative
/// control with other arithmetic).
struct Gradient {
  long* compiled_calls;
  double scale = 1;
  template <class Q, class G>
  void operator()(const Q& q, G& g) const {
    if constexpr (!std::is_same_v<Q, Eigen::VectorXd>) ++*compiled_calls;
    const Eigen::Index d = q.size();
    for (Eigen::Index i = 0; i < d; ++i) {
      const Eigen::Index next = (i + 1) % d, prev = (i + d - 1) % d;
      g[i] =
          scale * q[i] * q[i] * q[i] - 0.3 * q[i] + 0.1 * (2 * q[i] * q[next] + q[prev] * q[prev]);
    }
  }
};

/// Hess U v, for methods with modified kicks (the same on both paths: a std::function).
void hessian_vector(const Eigen::VectorXd& q, const Eigen::VectorXd& v, Eigen::VectorXd& Hv) {
  const Eigen::Index d = q.size();
  for (Eigen::Index i = 0; i < d; ++i) {
    const Eigen::Index next = (i + 1) % d, prev = (i + d - 1) % d;
    Hv[i] = (3 * q[i] * q[i] - 0.3) * v[i] +
            0.1 * (2 * q[next] * v[i] + 2 * q[i] * v[next] + 2 * q[prev] * v[prev]);
  }
}

/// Gradient with hessian_vector as its Hessian-vector product (the same arithmetic; scale
/// multiplies it: a negative control), counting its calls from the compiled steps in
/// *product_calls.
struct WithProduct : Gradient {
  long* product_calls;
  double product_scale = 1;
  template <class Q, class V, class H>
  void hessian_vector(const Q& q, const V& v, H& hv) const {
    if constexpr (!std::is_same_v<Q, Eigen::VectorXd>) ++*product_calls;
    Eigen::VectorXd out(q.size());
    ::erkn::test::hessian_vector(q, v, out);
    hv = product_scale * out;
  }
};

System system_without_gradient(Eigen::Index d, bool diagonal) {
  System s;
  s.M = diagonal ? Stiffness::diagonal(Eigen::VectorXd::LinSpaced(d, 4, 9)) : Stiffness::scalar(25);
  s.hessian_vector_product = hessian_vector;
  return s;
}

struct Outcome {
  Eigen::VectorXd q, p, observed;
  Statistics stats;
};

/// Steps, output times (on and off the grid) and a shorter last step; q, p at the end and what
/// the observer saw.
Outcome run(Integrator integrator) {
  Outcome r;
  integrator.integrate(0.8);
  Eigen::VectorXd times(3);
  times << 0.85, 1.0, 1.13;
  std::vector<double> seen;
  integrator.integrate(1.2, times, [&](double, const Eigen::VectorXd& q, const Eigen::VectorXd& p) {
    seen.insert(seen.end(), q.begin(), q.end()), seen.insert(seen.end(), p.begin(), p.end());
  });
  integrator.integrate(1.234);
  r.q = integrator.q(), r.p = integrator.p(), r.stats = integrator.statistics();
  r.observed = Eigen::Map<Eigen::VectorXd>(seen.data(), Eigen::Index(seen.size()));
  return r;
}

Outcome callback_run(const Method& m, Eigen::Index d, bool diagonal, const Options& o) {
  long calls = 0;
  System s = system_without_gradient(d, diagonal);
  const Gradient g{&calls};
  s.gradient = [g](const Eigen::VectorXd& q, Eigen::VectorXd& out) { g(q, out); };
  Outcome r = run(Integrator(m, s, 0.05, Eigen::VectorXd::LinSpaced(d, 0.3, 0.9),
                             Eigen::VectorXd::LinSpaced(d, -0.2, 0.4), o));
  EXPECT_EQ(calls, 0);
  return r;
}

Outcome compiled_run(const Method& m, Eigen::Index d, bool diagonal, const Options& o, long& calls,
                     double scale = 1) {
  return run(make_integrator(m, system_without_gradient(d, diagonal), Gradient{&calls, scale}, 0.05,
                             Eigen::VectorXd::LinSpaced(d, 0.3, 0.9),
                             Eigen::VectorXd::LinSpaced(d, -0.2, 0.4), o));
}

bool identical(const Outcome& a, const Outcome& b) {
  return a.q == b.q && a.p == b.p && a.observed == b.observed &&
         a.stats.gradient_evaluations == b.stats.gradient_evaluations &&
         a.stats.hessian_vector_products == b.stats.hessian_vector_products &&
         a.stats.processor_applications == b.stats.processor_applications &&
         a.stats.steps == b.stats.steps;
}

TEST(CompiledGradient, EveryExplicitMethodGivesTheCallbackPathsStatesBitForBit) {
  int cases = 0;
  for (const Method& m : Method::all()) {
    if (!m.is_explicit()) continue;
    for (Eigen::Index d = 1; d <= detail::kFixedMaxD; ++d)
      for (bool diagonal : {false, true})
        for (bool compensated : {false, true}) {
          SCOPED_TRACE(std::string(m.name()) + " d = " + std::to_string(d) +
                       (diagonal ? " diagonal" : " scalar") + (compensated ? " comp" : " plain"));
          Options o;
          o.compensated_summation = compensated;
          long calls = 0;
          const Outcome compiled = compiled_run(m, d, diagonal, o, calls);
          EXPECT_TRUE(identical(compiled, callback_run(m, d, diagonal, o)));
          // Every gradient of the compiled run was a call on fixed-size vectors.
          EXPECT_EQ(calls, compiled.stats.gradient_evaluations);
          ++cases;
        }
  }
  EXPECT_GE(cases, 16 * 10);
}

TEST(CompiledGradient, RknMethodsAddMQThroughCopiesOnEveryStructure) {
  // The registry's explicit methods as RKN methods (force M Q + grad U, the identity basis for
  // every M): the compiled steps take M Q through Eigen::VectorXd copies of Q and g; modified
  // kicks then call the System's product or (WithProduct) the functor's on the compiled vectors.
  const Eigen::MatrixXd dense = (Eigen::MatrixXd(3, 3) << 5, 1, 0, 1, 4, 1, 0, 1, 6).finished();
  const Stiffness structures[] = {Stiffness::scalar(25), Stiffness::dense(dense),
                                  Stiffness::circulant(Eigen::Vector3d(4, -1, -1))};
  for (const Method& m : Method::all()) {
    if (!m.is_explicit() || m.is_processed()) continue;
    generated::Table table = m.table();
    table.rkn = true;
    const Method rkn(m.id(), &table);
    for (const Stiffness& M : structures) {
      SCOPED_TRACE(std::string(m.name()) + " as RKN, structure " +
                   std::to_string(int(M.structure())));
      long calls = 0, unused = 0, products = 0;
      System s = system_without_gradient(3, false), bare = s;
      s.M = bare.M = M;
      bare.hessian_vector_product = nullptr;
      const Eigen::VectorXd q0 = Eigen::VectorXd::LinSpaced(3, 0.3, 0.9), p0 = -q0;
      const Outcome compiled = run(make_integrator(rkn, s, Gradient{&calls}, 0.02, q0, p0));
      const Outcome with_product =
          run(make_integrator(rkn, bare, WithProduct{{&unused}, &products}, 0.02, q0, p0));
      const Gradient g{&unused};
      s.gradient = [g](const Eigen::VectorXd& q, Eigen::VectorXd& out) { g(q, out); };
      const Outcome callback = run(Integrator(rkn, s, 0.02, q0, p0));
      EXPECT_TRUE(identical(compiled, callback));
      EXPECT_TRUE(identical(with_product, callback));
      EXPECT_EQ(calls, compiled.stats.gradient_evaluations);
      EXPECT_EQ(products, with_product.stats.hessian_vector_products);
    }
  }
}

TEST(CompiledGradient, NegativeControlsOtherArithmeticDiffersAndLargerSystemsUseTheCallback) {
  const Method& m = Method::by_name("SABA2");
  long calls = 0;
  // The comparison sees a change of the quartic coefficient by 2^-40.
  EXPECT_FALSE(identical(compiled_run(m, 2, true, {}, calls, 1 + std::ldexp(1.0, -40)),
                         callback_run(m, 2, true, {})));
  // d = 5 and implicit methods: System::gradient, the same functor (no fixed-size call).
  calls = 0;
  EXPECT_TRUE(identical(compiled_run(m, 5, true, {}, calls), callback_run(m, 5, true, {})));
  const Method& implicit = Method::by_name("SERKN2s3");
  EXPECT_TRUE(
      identical(compiled_run(implicit, 2, false, {}, calls), callback_run(implicit, 2, false, {})));
  EXPECT_EQ(calls, 0);
}

/// Every explicit method with M's half-spectrum basis (circulant M, d = 96, and a periodic grid
/// 8 x 12 when its transform is a half spectrum: with FFTW): the callback path's results bit for
/// bit, every gradient a compiled call; a moved quartic coefficient (2^-40) differs.
TEST(CompiledGradient, HalfSpectrumBasesGiveTheCallbackPathsStatesBitForBit) {
  Eigen::VectorXd column = Eigen::VectorXd::Zero(96);
  column[0] = 2.5, column[1] = column[95] = -1;
  const std::vector<GridAxis> axes{{8, 0.5, GridAxis::Boundary::periodic},
                                   {12, 0.4, GridAxis::Boundary::periodic}};
  const Stiffness structures[] = {Stiffness::circulant(column), Stiffness::grid(axes, 0.5)};
  const bool half_spectrum[] = {true, detail::half_spectrum_available(axes)};
  int cases = 0;
  for (const Method& m : Method::all()) {
    if (!m.is_explicit()) continue;
    for (int k = 0; k < 2; ++k)
      for (bool compensated : {false, true}) {
        SCOPED_TRACE(std::string(m.name()) + (k ? " grid" : " circulant") +
                     (compensated ? " comp" : " plain"));
        Options o;
        o.compensated_summation = compensated;
        System s = system_without_gradient(96, false);
        s.M = structures[k];
        const Eigen::VectorXd q0 = Eigen::VectorXd::LinSpaced(96, 0.3, 0.9), p0 = 0.5 - q0.array();
        long calls = 0, unused = 0;
        const Outcome compiled = run(make_integrator(m, s, Gradient{&calls}, 0.05, q0, p0, o));
        const Gradient g{&unused};
        s.gradient = [g](const Eigen::VectorXd& q, Eigen::VectorXd& out) { g(q, out); };
        EXPECT_TRUE(identical(compiled, run(Integrator(m, s, 0.05, q0, p0, o))));
        EXPECT_EQ(calls, half_spectrum[k] ? compiled.stats.gradient_evaluations : 0);
        EXPECT_EQ(unused, 0);
        if (cases == 0) {  // (negative control, once)
          s.gradient = nullptr;
          EXPECT_FALSE(identical(compiled, run(make_integrator(m, s, Gradient{&unused, 1 + 0x1p-40},
                                                               0.05, q0, p0, o))));
        }
        ++cases;
      }
  }
  EXPECT_GE(cases, 4 * 10);
}

/// A functor with hessian_vector: modified kicks call it on the compiled steps' vectors (d <= 4,
/// and circulant M, d = 96) with the callback path's results bit for bit; a product moved by
/// 2^-20 differs.
TEST(CompiledGradient, AFunctorsHessianVectorProductIsWhatModifiedKicksCall) {
  Eigen::VectorXd column = Eigen::VectorXd::Zero(96);
  column[0] = 2.5, column[1] = column[95] = -1;
  std::vector<std::pair<Eigen::Index, Stiffness>> scenes{{96, Stiffness::circulant(column)}};
  for (Eigen::Index d = 1; d <= detail::kFixedMaxD; ++d)
    for (bool diagonal : {false, true})
      scenes.emplace_back(d, system_without_gradient(d, diagonal).M);
  int cases = 0;
  for (const Method& m : Method::all()) {
    if (!m.is_explicit() || !m.has_modified_kicks()) continue;
    for (const auto& [d, M] : scenes) {
      SCOPED_TRACE(std::string(m.name()) + " d = " + std::to_string(d));
      System s;  // (neither gradient nor product: the functor's)
      s.M = M;
      const Eigen::VectorXd q0 = Eigen::VectorXd::LinSpaced(d, 0.3, 0.9), p0 = 0.5 - q0.array();
      long calls = 0, products = 0;
      const auto compiled_with = [&](double scale) {
        return run(make_integrator(m, s, WithProduct{{&calls}, &products, scale}, 0.05, q0, p0));
      };
      const Outcome compiled = compiled_with(1);
      EXPECT_EQ(products, compiled.stats.hessian_vector_products);
      EXPECT_GT(products, 0);
      System callback = system_without_gradient(d, false);
      callback.M = M;
      const Gradient g{&calls};
      callback.gradient = [g](const Eigen::VectorXd& q, Eigen::VectorXd& out) { g(q, out); };
      EXPECT_TRUE(identical(compiled, run(Integrator(m, callback, 0.05, q0, p0))));
      // (2^-20: the modified force is h^2 e_i G, and a 2^-40 change of it can round away)
      EXPECT_FALSE(identical(compiled, compiled_with(1 + 0x1p-20)));
      ++cases;
    }
  }
  EXPECT_GE(cases, 8 * 9);
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(CompiledGradient, RefusesWithTheRuntimesMessages) {
  const Method& m = Method::by_name("Yoshida4");
  const auto nan_after = [](double limit) {
    return [limit](const auto& q, auto& g) {
      for (Eigen::Index i = 0; i < q.size(); ++i) g[i] = q[i] > limit ? std::nan("") : -q[i];
    };
  };
  System s = system_without_gradient(2, true);
  const Eigen::VectorXd q0(Eigen::Vector2d(0.5, 0.1)), p0(Eigen::Vector2d(1, 0));
  std::string compiled, callback;
  compiled = error_of([&] { make_integrator(m, s, nan_after(0.6), 0.05, q0, p0).integrate(5); });
  System with_callback = s;
  with_callback.gradient = nan_after(0.6);
  callback = error_of([&] { Integrator(m, with_callback, 0.05, q0, p0).integrate(5); });
  EXPECT_NE(compiled.find("non-finite value"), std::string::npos) << compiled;
  EXPECT_EQ(compiled, callback);
  // Bad input: the constructor's checks.
  const Eigen::VectorXd q_bad(Eigen::Vector3d(0, 0, 0));
  compiled = error_of([&] { make_integrator(m, s, nan_after(1), 0.05, q_bad, p0); });
  callback = error_of([&] { Integrator(m, with_callback, 0.05, q_bad, p0); });
  EXPECT_NE(compiled.find("dimension mismatch"), std::string::npos) << compiled;
  EXPECT_EQ(compiled, callback);
  // Both gradients given.
  EXPECT_NE(error_of([&] {
              make_integrator(m, with_callback, nan_after(1), 0.05, q0, p0);
            }).find("System::gradient is set as well as the compiled gradient"),
            std::string::npos);
  // Both Hessian-vector products given (s has one).
  long calls = 0, products = 0;
  EXPECT_NE(error_of([&] {
              make_integrator(m, s, WithProduct{{&calls}, &products}, 0.05, q0, p0);
            }).find("System::hessian_vector_product is set as well as the compiled gradient's"),
            std::string::npos);
}

}  // namespace
}  // namespace erkn::test
