// The specialist's splitting loop (bench/specialist_peer.hpp) is the method it claims to be: for
// every explicit registry method, its observed order on smooth problems (a circulant M through
// FFTW r2c/c2r, a diagonal M through the identity) is the certified order, and its final state
// agrees with erkn::Integrator's on the benchmark's scenes to round-off. Negative control: d_1
// nudged by 5% breaks the order.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <erkn/erkn.hpp>
#include <erkn/problems.hpp>

#include "../tests/runtime/problems.hpp"
#include "integrate_timing.hpp"
#include "scenes.hpp"

namespace bench {
namespace {

using erkn::Method;
namespace problems = erkn::problems;

std::vector<Method> explicit_methods() {
  std::vector<Method> out;
  for (const Method& m : Method::all())
    if (m.is_explicit() && !m.has_modified_kicks() && !m.is_processed())
      out.push_back(m);  // (the peer: grad U kicks, no processor)
  return out;
}

// q(T) of the specialist's loop with n steps, d_1 scaled by (1 + nudge).
template <class Basis, class Gradient>
Eigen::VectorXd peer_q(const Method& m, const Basis& basis, Gradient g, const problems::Problem& p,
                       double T, long n, double nudge = 0) {
  std::vector<double> d(m.table().d, m.table().d + m.stages());
  d[0] *= 1 + nudge;
  specialist::Peer run(m.table().c, d.data(), m.stages(), T / double(n), basis, g, p.q0, p.p0);
  run.run(n);
  Eigen::VectorXd q, v;
  run.state(q, v);
  return q;
}

// The slope of log error over the four finest step counts n = 4, 6, 8, 11, ... (ratio sqrt 2,
// up to 16384) whose error is above kFloor. The floor sits above the peer's round-off: it sums
// plainly (no compensation), and its error at 16384 steps of sine-Gordon (|q| ~ 9) is 1e-13 or
// more.
constexpr double kFloor = 1e-12;
template <class F>
erkn::test::ObservedOrder observed_order(F&& error_at) {
  erkn::test::ObservedOrder o;
  for (int k = 0;; ++k) {
    const long n = std::lround(4 * std::pow(2.0, k / 2.0));
    const double err = n > 16384 ? 0 : error_at(n);
    if (err < kFloor) break;
    o.n.push_back(n), o.error.push_back(err);
  }
  if (o.n.size() < 4) return o;
  o.n.erase(o.n.begin(), o.n.end() - 4), o.error.erase(o.error.begin(), o.error.end() - 4);
  o.slope = erkn::test::fitted_slope(o.n, o.error);
  return o;
}

// Observed order against a long-double RK4 reference (tests/runtime/problems.hpp), and the
// nudged method's slope on the same step counts.
template <class Basis, class Gradient, class GradientLD>
void check_orders(const problems::Problem& p, const Basis& basis, Gradient g, GradientLD g_ld) {
  constexpr double T = 2;
  const Eigen::VectorXd ref =
      erkn::test::long_double_reference(p.M.dense(p.dim()), g_ld, p.q0, p.p0, {T}).q[0];
  for (const Method& m : explicit_methods()) {
    SCOPED_TRACE(std::string(m.name()) + " on " + p.title);
    auto error_at = [&](double nudge) {
      return [&, nudge](long n) { return (peer_q(m, basis, g, p, T, n, nudge) - ref).norm(); };
    };
    const erkn::test::ObservedOrder o = observed_order(error_at(0));
    ASSERT_EQ(o.n.size(), 4u) << "too few step sizes above the floor";
    std::vector<double> nudged;
    for (long n : o.n) nudged.push_back(error_at(5e-2)(n));
    const double nudged_slope = erkn::test::fitted_slope(o.n, nudged);
    std::printf(
        "%-9s %-24s order %d: observed %.3f (n = %ld..%ld, error %.0e..%.0e); nudged d_1: %.2f\n",
        std::string(m.name()).c_str(), p.title.c_str(), m.order(), o.slope, o.n.front(), o.n.back(),
        o.error.front(), o.error.back(), nudged_slope);
    EXPECT_NEAR(o.slope, m.order(), 0.15);
    EXPECT_LT(nudged_slope, m.order() - 0.5);
  }
}

// sine-Gordon with a strong nonlinearity (kappa = 4) on 8 points: M circulant, FFTW r2c/c2r.
TEST(SpecialistPeer, ObservedOrderIsTheCertifiedOrderInTheFourierBasis) {
  const problems::Problem p = problems::sine_gordon(8, 4);
  const specialist::FourierBasis basis = fourier_basis(p.M);
  auto g = [](const auto& q, auto& out) { out = 4 * q.sin(); };
  using VLD = erkn::test::VectorLD;
  check_orders(p, basis, g, [](const VLD& q) -> VLD { return 4 * q.array().sin().matrix(); });
}

// Stellar orbits with eps = 0.5 (the perturbation as large as the method's order shows).
TEST(SpecialistPeer, ObservedOrderIsTheCertifiedOrderInTheIdentityBasis) {
  const problems::Problem p = problems::stellar_orbits(0.5);
  const auto basis = identity_basis<2>(p.M, 2);
  using VLD = erkn::test::VectorLD;
  check_orders(p, basis, StellarGradient{0.5}, [](const VLD& q) -> VLD {
    VLD g(2);
    g << -0.5L * q[1] * q[1], -1.0L * q[0] * q[1];
    return g;
  });
}

// The final state of n steps against erkn's Integrator (compensated summation off: the same
// arithmetic up to the order of operations), relative to the state's size.
template <class Basis, class Gradient>
void check_agreement(const problems::Problem& p, const Basis& basis, Gradient g, double h, long n,
                     double bound) {
  for (const Method& m : explicit_methods()) {
    erkn::Options o;
    o.compensated_summation = false;
    erkn::Integrator run(m, problems::system(p), h, p.q0, p.p0, o);
    run.integrate(h * double(n));
    specialist::Peer peer(m.table().c, m.table().d, m.stages(), h, basis, g, p.q0, p.p0);
    peer.run(n);
    Eigen::VectorXd q, v;
    peer.state(q, v);
    const double dq = (q - run.q()).norm() / run.q().norm();
    const double dp = (v - run.p()).norm() / run.p().norm();
    std::printf("%-9s %-30s relative difference q %.1e, p %.1e\n", std::string(m.name()).c_str(),
                p.title.c_str(), dq, dp);
    EXPECT_LT(dq, bound) << m.name();
    EXPECT_LT(dp, bound) << m.name();
    EXPECT_EQ(peer.evaluations(), run.statistics().gradient_evaluations) << m.name();
  }
}

TEST(SpecialistPeer, AgreesWithTheIntegratorToRoundOff) {
  check_agreement(problems::duffing(), identity_basis<1>(problems::duffing().M, 1),
                  DuffingGradient{}, 1.0 / 100, 200, 1e-12);
  check_agreement(problems::stellar_orbits(), identity_basis<2>(problems::stellar_orbits().M, 2),
                  StellarGradient{}, 1.0 / 40, 200, 1e-12);
  for (int n : {32, 512}) {
    const problems::Problem p = problems::sine_gordon(n);
    check_agreement(p, fourier_basis(p.M), SineGordonGradient{}, 1.0 / 100, 50, 1e-12);
  }
  const problems::Problem p = problems::sine_gordon_2d(32);
  check_agreement(p, fourier_basis(p.M), SineGordonGradient{}, 1.0 / 40, 20, 1e-12);
}

// The peer through a callback on Eigen::VectorXd (VectorCallback: erkn_integrate_benchmark's
// peer through System::gradient) is the same loop: with the problems library's sine-Gordon
// gradient (sin, as SineGordonGradient) its final state has the inlined peer's bits in both
// bases, and with a gradient scaled by 1 + 2^-40 it does not (negative control).
template <class Basis, class Gradient>
void check_callback_peer(const problems::Problem& p, const Basis& basis, Gradient g, double h,
                         long n) {
  const erkn::System sys = problems::system(p);
  const auto scaled = [&](const Eigen::VectorXd& q, Eigen::VectorXd& out) {
    sys.gradient(q, out);
    out *= 1 + 0x1p-40;
  };
  for (const Method& m : explicit_methods()) {
    Eigen::VectorXd q[3], v[3];
    specialist::Peer inlined(m.table().c, m.table().d, m.stages(), h, basis, g, p.q0, p.p0);
    specialist::Peer callback(m.table().c, m.table().d, m.stages(), h, basis,
                              specialist::VectorCallback{sys.gradient}, p.q0, p.p0);
    specialist::Peer nudged(m.table().c, m.table().d, m.stages(), h, basis,
                            specialist::VectorCallback{scaled}, p.q0, p.p0);
    inlined.run(n), callback.run(n), nudged.run(n);
    inlined.state(q[0], v[0]), callback.state(q[1], v[1]), nudged.state(q[2], v[2]);
    EXPECT_TRUE(q[1] == q[0] && v[1] == v[0]) << m.name() << " on " << p.title;
    EXPECT_FALSE(q[2] == q[0] && v[2] == v[0]) << m.name() << " on " << p.title;
    EXPECT_EQ(callback.evaluations(), inlined.evaluations()) << m.name();
  }
}

TEST(SpecialistPeer, ThroughACallbackIsTheSameLoop) {
  const problems::Problem p = problems::sine_gordon(32);
  check_callback_peer(p, fourier_basis(p.M), SineGordonGradient{}, 1.0 / 40, 50);
  // (the identity basis: sine-Gordon's gradient with M's eigenvalues as a diagonal M)
  check_callback_peer(p, identity_basis<Eigen::Dynamic>(p.M, p.dim()), SineGordonGradient{},
                      1.0 / 40, 50);
}

// Blocks of one small size freed beyond what glibc's per-thread cache holds (7): the number of
// them left in fastbins (mallinfo2's smblks) for malloc_consolidate to merge later.
int small_blocks_left_in_fastbins() {
  std::vector<void*> blocks(32);
  for (void*& b : blocks) *static_cast<volatile char*>(b = std::malloc(48)) = 1;  // (kept)
  for (void* b : blocks) std::free(b);
  return int(mallinfo2().smblks);
}

// Whether a 4 MiB block is mapped (mallinfo2's hblks) while live, and whether freeing it gives
// pages back (the program break moves down: the heap trimmed).
struct LargeBlock {
  bool mapped, trimmed;
};
LargeBlock large_block() {
  void* b = std::malloc(size_t(4) << 20);
  static_cast<volatile char*>(b)[0] = 1;
  const bool mapped = mallinfo2().hblks > 0;
  void* live = sbrk(0);
  std::free(b);
  return {mapped, sbrk(0) < live};
}

// erkn_integrate_benchmark's timing keeps malloc steady (integrate_timing.hpp's header: with
// fastbins the heap state other cells leave made microsecond runs consolidate every run; with
// trimming or mmap the 256^2 grid's buffers came back as fresh pages). Negative controls: with
// glibc's defaults the same frees leave blocks in fastbins and the large block is mapped; with
// it taken from the heap but glibc's trim threshold, freeing it trims the heap.
TEST(Timing, SteadyMallocNoFastbinWaitsAndLargeBlocksStayInTheHeap) {
  ASSERT_EQ(mallopt(M_MXFAST, 64 * int(sizeof(size_t)) / 4), 1);  // (glibc's defaults)
  ASSERT_EQ(mallopt(M_MMAP_THRESHOLD, 128 * 1024), 1);
  ASSERT_EQ(mallopt(M_TRIM_THRESHOLD, 128 * 1024), 1);
  EXPECT_GT(small_blocks_left_in_fastbins(), 0);
  EXPECT_TRUE(large_block().mapped);
  ASSERT_EQ(mallopt(M_MMAP_THRESHOLD, 32 << 20), 1);
  EXPECT_TRUE(large_block().trimmed);
  ASSERT_TRUE(steady_malloc());
  EXPECT_EQ(small_blocks_left_in_fastbins(), 0);
  const LargeBlock steady = large_block();
  EXPECT_FALSE(steady.mapped);
  EXPECT_FALSE(steady.trimmed);
}

}  // namespace
}  // namespace bench
