// The floor loop of erkn_implicit_floor (bench/implicit_floor.hpp): for every implicit registry
// method its final state on P2 and P3 agrees with erkn's (same step count and tolerance; also the
// compensated, checked variant and the carry variant), its
// gradient evaluations are within 10 % of erkn's, the inlined and the callback loop give the same
// bits, and it reaches its order on Duffing (P2, exact solution known). Negative controls: a
// gradient off by a factor 1 + 1e-2 fails the agreement; U off by 1e-3 breaks the order.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "implicit_floor_runs.hpp"

namespace {

using namespace bench;
using floor::FloorRuns;
using floor::Variant;

using floor::kAgree;  // (the agreement with erkn's final state)

template <int D, class G>
void check_scene(FloorRuns<D, G>& r, const G& wrong) {
  for (const erkn::Method& m : erkn::Method::all()) {
    if (m.is_explicit()) continue;
    SCOPED_TRACE(std::string(m.name()) + " on " + r.s.label);
    Eigen::VectorXd qe, pe, qf, pf, qc, pc, qx, px, qw, pw;
    const long e = r.erkn(m, &qe, &pe), f = r.floor(m, r.g, Variant::plain, &qf, &pf);
    EXPECT_LE(floor::relative_diff(qe, pe, qf, pf), kAgree);
    EXPECT_NEAR(double(f), double(e), 0.1 * double(e));
    EXPECT_EQ(r.floor(m, r.callback(), Variant::plain, &qc, &pc), f);
    EXPECT_EQ(floor::state_diff(qf, pf, qc, pc), 0.0);     // (the same arithmetic)
    for (Variant v : {Variant::extras, Variant::carry}) {  // (compensated and checked; carry)
      EXPECT_NEAR(double(r.floor(m, r.callback(), v, &qx, &px)), double(e), 0.1 * double(e));
      EXPECT_LE(floor::relative_diff(qe, pe, qx, px), kAgree);
    }
    r.floor(m, wrong, Variant::plain, &qw, &pw);  // negative control
    EXPECT_GT(floor::relative_diff(qe, pe, qw, pw), kAgree);
  }
}

TEST(ImplicitFloor, FinalStatesAndEvaluationsAgreeWithErkn) {
  FloorRuns<1, DuffingGradient> p2{floor::duffing_scene(false), DuffingGradient{}, {}};
  DuffingGradient duffing_off;
  duffing_off.k2 *= 1 + 1e-2;
  check_scene(p2, duffing_off);
  FloorRuns<2, StellarGradient> p3{floor::stellar_scene(false), StellarGradient{}, {}};
  StellarGradient stellar_off;
  stellar_off.eps *= 1 + 1e-2;
  check_scene(p3, stellar_off);
}

// |q(T) - q_exact(T)| on Duffing at T = 2 with n steps of the floor loop, gradient g.
double duffing_error(const erkn::Method& m, long n, const DuffingGradient& g = {}) {
  erkn::problems::Problem p = erkn::problems::duffing();
  const double T = 2, h = T / double(n);
  Eigen::Array<double, 1, 1> lambda(p.M.eigenvalues(1)[0]), q0(p.q0[0]), p0(p.p0[0]);
  return floor::with_loop<1>(m, lambda, h, g, q0, p0, {}, [&](auto& loop) {
    loop.run(n);
    return std::abs(loop.q()[0] - (*p.exact)(T)[0]);
  });
}

// The observed order log2(e(n) / e(2n)) reaches the method's order (within 0.4).
TEST(ImplicitFloor, OrderOnDuffing) {
  for (const erkn::Method& m : erkn::Method::all()) {
    if (m.is_explicit()) continue;
    SCOPED_TRACE(std::string(m.name()));
    const long n = m.order() >= 6 ? 25 : 50;  // (round-off far below the error at order 6)
    const double e1 = duffing_error(m, n), e2 = duffing_error(m, 2 * n);
    EXPECT_GE(std::log2(e1 / e2), m.order() - 0.4) << e1 << " " << e2;
  }
}

// Negative control of the order test: against the exact solution of the right U, a loop with U
// off by 1e-3 keeps an O(1)-in-h error, and its observed order falls short.
TEST(ImplicitFloor, OrderTestFailsForAWrongGradient) {
  DuffingGradient off;
  off.k2 *= 1 + 1e-3;
  const erkn::Method& m = erkn::Method::by_name("SERKN2s3");
  EXPECT_LT(std::log2(duffing_error(m, 50, off) / duffing_error(m, 100, off)), m.order() - 0.4);
}

}  // namespace
