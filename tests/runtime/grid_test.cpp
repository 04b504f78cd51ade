// Tensor-grid M (Stiffness::grid): closed-form eigenvalues against a dense eigendecomposition,
// the transforms (FFTW or the separable fallback) against each other and against M, and the
// integrator on grid M against the dense path, exact for U = 0, of its order and symplectic.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "grid_backend.hpp"
#include "m_operator.hpp"
#include "problems.hpp"

namespace erkn::test {
namespace {

using B = GridAxis::Boundary;
constexpr B kBoundaries[] = {B::periodic, B::dirichlet, B::neumann};

// Small grids that cover k = 1, 2, 3, every boundary per axis, odd and even n, n = 1 and 2.
std::vector<std::pair<std::vector<GridAxis>, double>> small_grids() {
  std::vector<std::pair<std::vector<GridAxis>, double>> out;
  for (B b : kBoundaries)
    for (Eigen::Index n : {1, 2, 5, 8}) out.push_back({{{n, 0.3, b}}, 0.0});
  for (B b0 : kBoundaries)
    for (B b1 : kBoundaries) out.push_back({{{4, 0.5, b0}, {5, 0.25, b1}}, 2.0});
  out.push_back({{{3, 1.0, B::dirichlet}, {4, 0.5, B::periodic}, {3, 2.0, B::neumann}}, 0.5});
  out.push_back({{{2, 0.7, B::neumann}, {3, 0.4, B::neumann}, {4, 0.2, B::periodic}}, 0.0});
  return out;
}

std::string describe(const std::vector<GridAxis>& axes) {
  const char* names[] = {"periodic", "dirichlet", "neumann"};
  std::string s;
  for (const GridAxis& a : axes)
    s += std::to_string(a.n) + " " + names[int(a.boundary)] + (&a == &axes.back() ? "" : " x ");
  return s;
}

TEST(Grid, ClosedFormEigenvaluesAreThoseOfTheDenseStencilMatrix) {
  for (const auto& [axes, shift] : small_grids()) {
    SCOPED_TRACE(describe(axes));
    const Stiffness M = Stiffness::grid(axes, shift);
    const Eigen::MatrixXd dense = M.to_dense(M.dim());
    ASSERT_LE((dense - dense.transpose()).cwiseAbs().maxCoeff(), 0.0) << "not symmetric";
    Eigen::VectorXd closed = M.eigenvalues(), exact = Stiffness::dense(dense).eigenvalues();
    std::sort(closed.begin(), closed.end());
    const double scale = exact.cwiseAbs().maxCoeff();
    EXPECT_LE((closed - exact).cwiseAbs().maxCoeff(), 1e-12 * scale);
  }
}

TEST(Grid, NegativeControlAnotherBoundaryHasOtherEigenvalues) {
  for (B b : kBoundaries)
    for (B other : kBoundaries) {
      if (b == other) continue;
      const Stiffness M = Stiffness::grid({{6, 0.5, b}}), W = Stiffness::grid({{6, 0.5, other}});
      Eigen::VectorXd lm = M.eigenvalues(), lw = W.eigenvalues();
      std::sort(lm.begin(), lm.end()), std::sort(lw.begin(), lw.end());
      EXPECT_GE((lm - lw).cwiseAbs().maxCoeff(), 0.1);
    }
}

// For both backends: inverse(forward(x)) = x, the weighted norm is |x|, and
// inverse(lambda * forward(x)) = M x (the stencil operator and the dense matrix).
TEST(Grid, TransformsDiagonaliseM) {
  for (const auto& [axes, shift] : small_grids()) {
    SCOPED_TRACE(describe(axes));
    const Stiffness M = Stiffness::grid(axes, shift);
    const Eigen::Index d = M.dim();
    const Eigen::VectorXd x = random_vector(d, 7);
    const Eigen::VectorXd Mx = M.to_dense(d) * x;
    Eigen::VectorXd stencil(d);
    detail::MOperator(M, d).apply(x, stencil);
    EXPECT_LE((stencil - Mx).cwiseAbs().maxCoeff(), 1e-12 * Mx.cwiseAbs().maxCoeff());
    auto fallback = detail::make_separable_backend(axes), main = detail::make_grid_backend(axes);
    detail::GridTransform t(axes);
    Eigen::VectorXd y(d), y2(d), back(d);
    for (detail::GridBackend* backend : {fallback.get(), main.get()}) {
      backend->forward(x.data(), y.data());
      backend->inverse(y.data(), back.data());
      EXPECT_LE((back - x).cwiseAbs().maxCoeff(), 1e-13);
      EXPECT_NEAR(std::sqrt(t.squared_norm(y.array())), x.norm(), 1e-13 * x.norm());
      y2 = (M.eigenvalues().array() * y.array()).matrix();
      backend->inverse(y2.data(), back.data());
      EXPECT_LE((back - Mx).cwiseAbs().maxCoeff(), 1e-12 * Mx.cwiseAbs().maxCoeff());
    }
    // Negative control: the eigenvalues in another order do not diagonalise M (unless constant).
    fallback->forward(x.data(), y.data());
    y2 = (M.eigenvalues().reverse().array() * y.array()).matrix();
    fallback->inverse(y2.data(), back.data());
    if (M.eigenvalues().maxCoeff() - M.eigenvalues().minCoeff() > 1e-9 &&
        M.eigenvalues() != M.eigenvalues().reverse())
      EXPECT_GE((back - Mx).cwiseAbs().maxCoeff(), 1e-6);
  }
}

// max |(q, p)_grid - (q, p)_dense| / max |(q, p)| over 20 steps of q'' + M q = -sin q.
double grid_dense_difference(const Method& m, const Stiffness& M, double h) {
  const Eigen::Index d = M.dim();
  const Eigen::VectorXd q0 = random_vector(d, 1), p0 = random_vector(d, 2);
  Integrator a(m, sine_gordon(M), h, q0, p0),
      b(m, sine_gordon(Stiffness::dense(M.to_dense(d))), h, q0, p0);
  double diff = 0;
  for (int n = 0; n < 20; ++n) {
    a.step(), b.step();
    const double scale = std::max(b.q().cwiseAbs().maxCoeff(), b.p().cwiseAbs().maxCoeff());
    diff = std::max({diff, (a.q() - b.q()).cwiseAbs().maxCoeff() / scale,
                     (a.p() - b.p()).cwiseAbs().maxCoeff() / scale});
  }
  return diff;
}

TEST(Grid, IntegratorAgreesWithTheDensePathForEveryMethod) {
  const auto grids = small_grids();
  for (const Method& m : Method::all())
    for (std::size_t g = 0; g < grids.size(); g += 3) {  // (a third of them: every method x k)
      const Stiffness M = Stiffness::grid(grids[g].first, grids[g].second);
      SCOPED_TRACE(std::string(m.name()) + " " + describe(grids[g].first));
      const double h = m.kind() == Kind::rkn ? 0.02 : 0.1;
      EXPECT_LE(grid_dense_difference(m, M, h), 1e-12);
    }
}

// Circulant M beyond the Fourier basis size goes through the FFT (FFTW's halfcomplex transform
// when built with it): the same trajectory as the dense path, even and odd N.
TEST(Grid, CirculantBeyondTheFourierBasisSizeAgreesWithTheDensePath) {
  for (int N : {100, 101}) {
    const Stiffness circ = Stiffness::circulant(sine_gordon_column(N));
    for (const Method& m : Method::all()) {
      SCOPED_TRACE(std::string(m.name()) + " N = " + std::to_string(N));
      const Eigen::VectorXd q0 = random_vector(N, 10), p0 = random_vector(N, 11);
      const double h = m.kind() == Kind::rkn ? 0.002 : 0.05;
      Integrator a(m, sine_gordon(circ), h, q0, p0),
          b(m, sine_gordon(Stiffness::dense(circ.to_dense(N))), h, q0, p0);
      for (int n = 0; n < 10; ++n) a.step(), b.step();
      const double scale = std::max(b.q().cwiseAbs().maxCoeff(), b.p().cwiseAbs().maxCoeff());
      EXPECT_LE((a.q() - b.q()).cwiseAbs().maxCoeff() / scale, 1e-12);
      EXPECT_LE((a.p() - b.p()).cwiseAbs().maxCoeff() / scale, 1e-12);
    }
  }
}

// q(t) = cos(t sqrt(M)) q0 + sin(t sqrt(M)) / sqrt(M) p0 from the dense eigendecomposition.
Eigen::VectorXd exact_linear(const Stiffness& M, double t, const Eigen::VectorXd& q0,
                             const Eigen::VectorXd& p0) {
  const Stiffness D = Stiffness::dense(M.to_dense(M.dim()));
  const Eigen::MatrixXd& E = D.eigenvectors();
  const Eigen::ArrayXd w = D.eigenvalues().array().sqrt();
  const Eigen::ArrayXd a = E.transpose() * q0, b = E.transpose() * p0;
  const Eigen::ArrayXd sinc = (w > 0).select((w * t).sin() / w.max(1e-300), t);
  return E * ((w * t).cos() * a + sinc * b).matrix();
}

TEST(Grid, ErknMethodsAreExactForUZeroAtLargeStepsAndRknLimitsAreNot) {
  const Stiffness M = Stiffness::grid({{6, 0.1, B::dirichlet}, {5, 0.2, B::periodic}}, 3.0);
  const Eigen::VectorXd q0 = random_vector(M.dim(), 3), p0 = random_vector(M.dim(), 4);
  const double h = 0.7;  // h^2 lambda_max ~ 240
  const Eigen::VectorXd exact = exact_linear(M, 10 * h, q0, p0);
  for (const Method& m : Method::all()) {
    SCOPED_TRACE(std::string(m.name()));
    System s;
    s.M = M;
    s.gradient = [](const Eigen::VectorXd&, Eigen::VectorXd& g) { g.setZero(); };
    s.hessian_vector_product = [](const Eigen::VectorXd&, const Eigen::VectorXd& v,
                                  Eigen::VectorXd& hv) { hv.setZero(v.size()); };
    if (m.kind() == Kind::rkn) {  // negative control: not exact (unstable at h = 0.7), even at
      Integrator run(m, s, 0.01, q0, p0);  // h = 0.01 1e3 times above the ERKN bound below
      for (int n = 0; n < 700; ++n) run.step();
      EXPECT_GE((run.q() - exact).cwiseAbs().maxCoeff(), 1e-9 * exact.cwiseAbs().maxCoeff());
      continue;
    }
    Integrator run(m, s, h, q0, p0);
    for (int n = 0; n < 10; ++n) run.step();
    EXPECT_LE((run.q() - exact).cwiseAbs().maxCoeff(), 1e-12 * exact.cwiseAbs().maxCoeff());
  }
}

// A 2 x 3 grid (periodic x Dirichlet, shift 1) with U = -sum cos q: small enough for a dense RK4
// reference and a finite-difference Jacobian of the one-step map.
Stiffness small_grid() {
  return Stiffness::grid({{2, 0.8, B::periodic}, {3, 0.6, B::dirichlet}}, 1.0);
}

// The fit of order_test.cpp (observed_order: errors >= 1e-13 against a long-double reference,
// stage equations solved to round-off).
TEST(Grid, ObservedOrderOfEveryMethodOnAGridIsItsClaimedOrder) {
  const Stiffness M = small_grid();
  const System s = sine_gordon(M);
  const double T = 2;
  const Eigen::VectorXd q0 = random_vector(6, 5), p0 = random_vector(6, 6);
  auto reference_at = [&](double t) {
    return long_double_reference(
        M.to_dense(6), [](const VectorLD& x) -> VectorLD { return x.array().sin(); }, q0, p0, {t});
  };
  const Reference ref = reference_at(T);
  // A floor 10x below kOrderFloor: on this small grid OMF8(11F11G)'s error falls from 6e-11 to
  // 2e-13 between T/16 and T/32, before its asymptotic range (local slopes 8.25, 8.13; 8.05 at
  // T/23..T/45 with this floor). The reference (accuracy 1.5e-16) stays 50 times below it: a
  // relative error of 2 % at the floor, about 0.03 in a slope fitted over a factor 2 in h.
  constexpr double floor = kOrderFloor / 10;
  EXPECT_LT(ref.accuracy, floor / 50);
  // Processed methods over 10 T, as in order_test.cpp (over T, pi's error at the ends, which
  // does not grow, steepens the slope: PMLF6's local slopes 6.92, 6.55, 5.97 at T/16..T/128).
  // Over 10 T a run's round-off reaches 1e-14..3e-14 (PMLF6 at T/256..T/4096), so they fit
  // above 1e-12 (PMLF6: 6.16, 5.90 at T/16..T/64; PMLF4 and PLF7_6_4: 4.02..4.06).
  const Reference ref_long = reference_at(10 * T);
  constexpr double processed_floor = kOrderFloor * 10;
  EXPECT_LT(ref_long.accuracy, processed_floor / 50);
  Options solved_to_round_off;
  solved_to_round_off.tolerance = 0;
  for (const Method& m : Method::all()) {
    SCOPED_TRACE(std::string(m.name()));
    const ObservedOrder o = observed_order(
        [&](long n) {
          Integrator run(m, s, T / double(n), q0, p0, solved_to_round_off);
          run.integrate(m.is_processed() ? 10 * T : T);
          return (run.q() - (m.is_processed() ? ref_long : ref).q[0]).norm();
        },
        m.is_processed() ? processed_floor : floor);
    ASSERT_GE(o.n.size(), 3u);
    std::printf("%-14s certified order %d: observed on a grid %.3f (h = T/%ld..T/%ld)\n",
                std::string(m.name()).c_str(), m.order(), o.slope, o.n.front(), o.n.back());
    EXPECT_NEAR(o.slope, m.order(), 0.15);
  }
}

double grid_symplecticity_defect(const Method& m, double h) {
  const int d = 6;
  Eigen::VectorXd y(2 * d);
  y << random_vector(d, 8), random_vector(d, 9);
  return symplecticity_defect(m, sine_gordon(small_grid()), h, y);
}

TEST(Grid, OneStepMapOnAGridIsSymplecticAndANudgedMethodIsNot) {
  for (const Method& m : Method::all()) {
    SCOPED_TRACE(std::string(m.name()));
    EXPECT_LE(grid_symplecticity_defect(m, 0.2), 1e-9);
    if (m.is_explicit()) continue;  // the nudged coefficient is one the explicit path never reads
    EXPECT_GE(grid_symplecticity_defect(perturbed(m), 0.2), 1e-6);
  }
}

TEST(Grid, BadAxesAndShiftsAreRefusedWithAClearError) {
  auto message = [](auto&& f) {
    try {
      f();
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  auto contains = [](const std::string& s, const char* part) {
    return s.find(part) != std::string::npos;
  };
  EXPECT_TRUE(contains(message([] { Stiffness::grid({}); }), "at least one axis"));
  EXPECT_TRUE(contains(message([] { Stiffness::grid({{0, 1.0, B::periodic}}); }), "n = 0"));
  EXPECT_TRUE(contains(message([] { Stiffness::grid({{4, -1.0, B::periodic}}); }), "spacing"));
  EXPECT_TRUE(contains(message([] { Stiffness::grid({{4, NAN, B::periodic}}); }), "spacing"));
  EXPECT_TRUE(contains(message([] {
                         Stiffness::grid({{4, 1.0, B::periodic}}, NAN);
                       }),
                       "not finite"));
  // Periodic and Neumann have eigenvalue 0, so any negative shift makes M indefinite; Dirichlet
  // tolerates a shift down to -mu_0.
  EXPECT_TRUE(contains(message([] {
                         Stiffness::grid({{4, 1.0, B::neumann}}, -1e-3);
                       }),
                       "not positive semi-definite"));
  const double mu0 = GridAxis{4, 1.0, B::dirichlet}.eigenvalues()[0];
  EXPECT_EQ(message([&] { Stiffness::grid({{4, 1.0, B::dirichlet}}, -0.5 * mu0); }), "no error");
  EXPECT_TRUE(contains(message([&] {
                         Stiffness::grid({{4, 1.0, B::dirichlet}}, -1.5 * mu0);
                       }),
                       "not positive semi-definite"));
  System s;
  s.M = Stiffness::grid({{4, 1.0, B::periodic}, {3, 1.0, B::dirichlet}});
  s.gradient = [](const Eigen::VectorXd&, Eigen::VectorXd& g) { g.setZero(); };
  EXPECT_TRUE(contains(message([&] {
                         Integrator(Method::all()[0], s, 0.1, Eigen::VectorXd::Zero(11),
                                    Eigen::VectorXd::Zero(11));
                       }),
                       "dimension mismatch"));
}

}  // namespace
}  // namespace erkn::test
