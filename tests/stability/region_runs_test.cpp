// Runs of the integrator on the test equation at points picked from the computed regions (the
// grid the chart shows): bounded inside, growing like rho(S)^n outside.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "support.hpp"

namespace erkn {
namespace {

constexpr double kH = 0.1;  // any h: the runs depend on (V, z) only

StabilityGrid chart_grid(const Method& m) { return stability_grid(m, 100, -50, 50, 101, 101); }

// Every point with V + z > 0 (bounded exact solution), V at least 2 % away from every pole.
bool admissible(const Method& m, const StabilityPoint& p) {
  return p.V + p.z > 0 && test::away_from_poles(m, p.V, 0.02);
}

// The invariant quadratic form of a symplectic 2x2 S with |tr S| < 2: Q = J (S - tr/2 I),
// normalised positive definite. S^T Q S = Q, so |x_n|_Q is constant and
// |x_n| <= sqrt(cond Q) |x_0| for all n.
Eigen::Matrix2d invariant_form(const StabilityMatrix& S) {
  Eigen::Matrix2d Q;
  Q << S.s21, 0.5 * (S.s22 - S.s11), 0.5 * (S.s22 - S.s11), -S.s12;
  return Q(0, 0) < 0 ? Eigen::Matrix2d(-Q) : Q;
}

struct BoundedRun {
  double max_growth = 0;  // max_n |x_n| / |x_0|
  double bound = 0;       // sqrt(cond Q)
  double form_drift = 0;  // max_n | |x_n|_Q / |x_0|_Q - 1 |
};

BoundedRun run_bounded(const Method& m, const StabilityPoint& p, long steps) {
  const StabilityMatrix S = stability_matrix(m, p.V, p.z);
  const Eigen::Matrix2d Q = invariant_form(S);
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(Q);
  BoundedRun r;
  r.bound = std::sqrt(es.eigenvalues()[1] / es.eigenvalues()[0]);
  // The growth is bounded here against S's own bound, tighter than the blow-up guard's factor
  // 1e4 in energy, which a processed method's state (P x, cond P up to ~1e2 at z ~ 20) can
  // exceed on a bounded run.
  Options bounded_here;
  bounded_here.blowup_guard = false;
  Integrator run(m, test::test_equation(p.V, p.z, kH), kH, test::scalar(1), test::scalar(0),
                 bounded_here);
  const Eigen::Vector2d x0(1, 0);
  const double n0 = x0.norm(), q0 = std::sqrt(x0.dot(Q * x0));
  for (long n = 0; n < steps; ++n) {
    run.step();
    const Eigen::Vector2d x(run.q()[0], kH * run.p()[0]);
    r.max_growth = std::max(r.max_growth, x.norm() / n0);
    r.form_drift = std::max(r.form_drift, std::abs(std::sqrt(x.dot(Q * x)) / q0 - 1));
    if (!std::isfinite(x.norm())) break;
  }
  return r;
}

// Points well inside the periodicity region (|tr S| <= 1.9 at the point and its 8 grid
// neighbours): the integrator's solution stays within the bound of S over 1e5 steps, and the
// invariant norm of S is conserved to 1e-7 (round-off and stage tolerance
// accumulate ~1e-9 over 1e5 steps).
TEST(RegionRuns, InsidePointsStayBoundedOver1e5Steps) {
  for (const Method& m : Method::all()) {
    const StabilityGrid g = chart_grid(m);
    const auto inside = test::interior_points(g, [&](const StabilityPoint& p) {
      return admissible(m, p) && p.cls == StabilityClass::periodic && std::abs(p.trace) <= 1.9;
    });
    ASSERT_FALSE(inside.empty()) << m.name();
    // Three picks: the largest V, the most negative z, the largest |z| * V.
    const StabilityPoint picks[] = {
        *std::max_element(inside.begin(), inside.end(),
                          [](auto& a, auto& b) { return a.V + 1e-9 * a.z < b.V + 1e-9 * b.z; }),
        *std::min_element(inside.begin(), inside.end(), [](auto& a, auto& b) { return a.z < b.z; }),
        *std::max_element(inside.begin(), inside.end(), [](auto& a, auto& b) {
          return std::abs(a.z) * a.V < std::abs(b.z) * b.V;
        })};
    for (const StabilityPoint& p : picks) {
      const BoundedRun r = run_bounded(m, p, 100000);
      EXPECT_LE(r.max_growth, r.bound * (1 + 1e-7))
          << m.name() << " V=" << p.V << " z=" << p.z << " tr=" << p.trace;
      // (|x|_Q carries a round-off ~ eps cond Q = eps bound^2: 5e-3 for PMLF6's conjugated S
      // at V = 62, z = -46, whose cond Q is 3.7e14; 1e-7 for every bound below ~2e3)
      const double roundoff = 64 * std::numeric_limits<double>::epsilon() * r.bound * r.bound;
      EXPECT_LE(r.form_drift, std::max(1e-7, roundoff)) << m.name() << " V=" << p.V << " z=" << p.z;
      RecordProperty(
          std::string(m.id_name()) + "_V" + std::to_string(p.V) + "_z" + std::to_string(p.z),
          "growth " + std::to_string(r.max_growth) + " bound " + std::to_string(r.bound) +
              " drift " + std::to_string(r.form_drift));
    }
  }
}

// Points outside (unstable with rho(S) >= 1.02 at the point and its neighbours, rho <= 10 at the
// point, V + z > 0 so the exact solution is bounded): the solution grows like rho(S)^n, the
// measured rate within 1 %. Methods without such points must have no admissible unstable grid
// point at all (the chart then claims: bounded for every V + z > 0 charted).
TEST(RegionRuns, OutsidePointsGrowLikeRhoToTheN) {
  int methods_with_outside_points = 0;
  for (const Method& m : Method::all()) {
    const StabilityGrid g = chart_grid(m);
    auto outside = test::interior_points(g, [&](const StabilityPoint& p) {
      return admissible(m, p) && p.cls == StabilityClass::unstable && p.rho >= 1.02;
    });
    std::erase_if(outside, [](const StabilityPoint& p) { return p.rho > 10; });
    if (outside.empty()) {
      for (const StabilityPoint& p : g.points)
        EXPECT_TRUE(!admissible(m, p) || bounded_region(p.cls))
            << m.name() << " V=" << p.V << " z=" << p.z << " " << to_string(p.cls);
      RecordProperty(std::string(m.id_name()) + "_outside", "none with V + z > 0");
      continue;
    }
    ++methods_with_outside_points;
    // Two picks: the smallest rho (slowest growth) and the largest.
    auto by_rho = [](auto& a, auto& b) { return a.rho < b.rho; };
    for (const StabilityPoint& p : {*std::min_element(outside.begin(), outside.end(), by_rho),
                                    *std::max_element(outside.begin(), outside.end(), by_rho)}) {
      const double rho = stability_matrix(m, p.V, p.z).spectral_radius();
      const long steps = long(std::ceil(60 * std::log(10.0) / std::log(rho)));  // rho^n ~ 1e60
      Options growth_wanted;  // the blow-up guard would stop the growth this test measures
      growth_wanted.blowup_guard = false;
      Integrator run(m, test::test_equation(p.V, p.z, kH), kH, test::scalar(1), test::scalar(0),
                     growth_wanted);
      double log_half = 0, log_end = 0;
      for (long n = 1; n <= steps; ++n) {
        run.step();
        const double lx = std::log(std::hypot(run.q()[0], kH * run.p()[0]));
        if (n == steps / 2) log_half = lx;
        if (n == steps) log_end = lx;
      }
      const double measured = std::exp((log_end - log_half) / double(steps - steps / 2));
      EXPECT_NEAR(measured / rho, 1.0, 0.01) << m.name() << " V=" << p.V << " z=" << p.z;
      RecordProperty(
          std::string(m.id_name()) + "_V" + std::to_string(p.V) + "_z" + std::to_string(p.z),
          "rho " + std::to_string(rho) + " measured " + std::to_string(measured));
      // Negative control: the boundedness criterion of the inside test fails here.
      EXPECT_GT(measured, 1.01);
    }
  }
  EXPECT_GE(methods_with_outside_points, 10);
}

}  // namespace
}  // namespace erkn
