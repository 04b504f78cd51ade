// The implicit step's passes (implicit_passes.hpp) compute the bits of Eigen's expressions of the
// same arithmetic, which the stepper evaluated before them: eq. (d)'s update on real and complex
// eigen coordinates (one coefficient, or one per coordinate), for 1 to 5 stages, plain and
// compensated, with the non-finite bits of q + dq and p + dp. Negative control: one coefficient
// times 1 + 2^-40 changes the bits.
#include "implicit_passes.hpp"

#include <gtest/gtest.h>

#include <array>
#include <complex>
#include <cstring>
#include <limits>
#include <random>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

namespace erkn::detail {
namespace {

constexpr Eigen::Index kCoordinates = 37;

// Random eigen coordinates (Scalar double or complex) and real coefficients, one seed.
template <class Scalar>
struct UpdateData {
  using Array = Eigen::Array<Scalar, Eigen::Dynamic, 1>;
  UpdateData(int s, unsigned seed) : rng(seed) {
    q = random(), p = random(), eq = random() * 1e-17, ep = random() * 1e-17;
    for (int i = 0; i < s; ++i)
      g.push_back(random()), h2bbar.push_back(real()), hb.push_back(real());
    phi0m1 = real(), hphi1 = real(), mhMphi1 = real();
  }
  Eigen::ArrayXd real() {
    return Eigen::ArrayXd::NullaryExpr(kCoordinates, [&] { return u(rng); });
  }
  Array random() {
    if constexpr (std::is_same_v<Scalar, double>)
      return real();
    else
      return real().template cast<Scalar>() + Scalar(0, 1) * real().template cast<Scalar>();
  }
  std::mt19937_64 rng;
  std::uniform_real_distribution<double> u{-2, 2};
  Array q, p, eq, ep;
  std::vector<Array> g;
  std::vector<Eigen::ArrayXd> h2bbar, hb;
  Eigen::ArrayXd phi0m1, hphi1, mhMphi1;
};

template <class A>
std::vector<unsigned char> bytes(const A& a) {
  std::vector<unsigned char> b(sizeof(typename A::Scalar) * size_t(a.size()));
  std::memcpy(b.data(), a.data(), b.size());
  return b;
}
template <class Scalar>
double* lanes(Eigen::Array<Scalar, Eigen::Dynamic, 1>& a) {
  return reinterpret_cast<double*>(a.data());
}

// The bytes of q, p, eq, ep.
template <class Scalar>
std::vector<unsigned char> state_bytes(const UpdateData<Scalar>& d) {
  std::vector<unsigned char> out;
  for (const auto* a : {&d.q, &d.p, &d.eq, &d.ep}) {
    const std::vector<unsigned char> b = bytes(*a);
    out.insert(out.end(), b.begin(), b.end());
  }
  return out;
}

// The state after the update, by Eigen's expressions (the stepper's before the passes), or by
// the passes (bits: the passes' non-finite bits).
template <class Scalar>
std::vector<unsigned char> by_expressions(UpdateData<Scalar> d, bool kahan) {
  typename UpdateData<Scalar>::Array dq = d.phi0m1 * d.q + d.hphi1 * d.p,
                                     dp = d.mhMphi1 * d.q + d.phi0m1 * d.p;
  for (size_t i = 0; i < d.g.size(); ++i) dq -= d.h2bbar[i] * d.g[i], dp -= d.hb[i] * d.g[i];
  const auto add = [&](auto& x, auto& e, auto& dx) {
    if (kahan)
      compensated_add(x, e, dx);
    else
      x += dx;
  };
  add(d.q, d.eq, dq), add(d.p, d.ep, dp);
  return state_bytes(d);
}
template <class Scalar>
std::vector<unsigned char> by_passes(UpdateData<Scalar> d, bool kahan, UpdateBits& bits) {
  constexpr int kLanes = int(sizeof(Scalar) / sizeof(double));
  typename UpdateData<Scalar>::Array dq(kCoordinates), dp(kCoordinates);
  const UpdateCoefficients<const double*> k{d.phi0m1.data(), d.hphi1.data(), d.mhMphi1.data()};
  bits = update_passes<kLanes>(
      int(d.g.size()), kCoordinates, lanes(d.q), lanes(d.p), lanes(dq), lanes(dp), k, [&](int i) {
        return std::tuple{lanes(d.g[size_t(i)]), d.h2bbar[size_t(i)].data(),
                          d.hb[size_t(i)].data()};
      });
  if (kahan)
    add_pass<kLanes, true>(kCoordinates, lanes(d.q), lanes(d.eq), lanes(dq)),
        add_pass<kLanes, true>(kCoordinates, lanes(d.p), lanes(d.ep), lanes(dp));
  else
    add_pass<kLanes, false>(kCoordinates, lanes(d.q), lanes(d.eq), lanes(dq)),
        add_pass<kLanes, false>(kCoordinates, lanes(d.p), lanes(d.ep), lanes(dp));
  return state_bytes(d);
}

template <class Scalar>
void check_update() {
  for (int s = 1; s <= 5; ++s)
    for (bool kahan : {false, true}) {
      SCOPED_TRACE("stages " + std::to_string(s) + (kahan ? ", compensated" : ", plain"));
      UpdateData<Scalar> d(s, 20261127u + unsigned(s));
      UpdateBits bits;
      EXPECT_EQ(by_passes(d, kahan, bits), by_expressions(d, kahan));
      EXPECT_EQ(bits.q, 0u);
      EXPECT_EQ(bits.p, 0u);
      UpdateData<Scalar> nudged = d;
      nudged.hb[size_t(s - 1)][11] *= 1 + 0x1p-40;  // (negative control)
      EXPECT_NE(by_passes(nudged, kahan, bits), by_expressions(d, kahan));
    }
}

TEST(ImplicitPasses, UpdateGivesTheBitsOfEigensExpressions) {
  check_update<double>();
  check_update<std::complex<double>>();
}

// A non-finite gradient entry makes q + dq non-finite (bits.q), an infinite h b_i only p + dp.
TEST(ImplicitPasses, UpdateTakesTheNonFiniteBitsOfTheResult) {
  for (int s : {1, 3}) {
    UpdateData<std::complex<double>> d(s, 7u);
    d.g[0][5] = std::numeric_limits<double>::quiet_NaN();
    UpdateBits bits;
    by_passes(d, false, bits);
    EXPECT_NE(bits.q, 0u);
    UpdateData<std::complex<double>> e(s, 7u);
    e.hb[size_t(s - 1)][3] = std::numeric_limits<double>::infinity();
    by_passes(e, true, bits);
    EXPECT_EQ(bits.q, 0u);
    EXPECT_NE(bits.p, 0u);
  }
}

// The fixed point's pass (iterate_pass) gives the bits of the expressions the stage solver
// evaluates without it: Q_new = r - abar g, the half spectrum's squared norms of Q_new - Q and
// Q_new, and the inverse transform's scaled copy of Q_new.
TEST(ImplicitPasses, IterateGivesTheBitsOfEigensExpressions) {
  for (double nudge : {0.0, 0x1p-40}) {
    UpdateData<std::complex<double>> d(1, 99u);
    const Eigen::ArrayXcd& r = d.q;
    const Eigen::ArrayXcd &Q = d.p, &g = d.g[0];
    const Eigen::ArrayXd abar = d.hphi1, w = d.phi0m1.abs();
    const double scale = 1.0 / 64;
    const Eigen::ArrayXcd expected = r - abar * g;
    const std::array<double, 2> sums{(w * (expected - Q).abs2()).sum(),
                                     (w * expected.abs2()).sum()};
    Eigen::ArrayXcd next(kCoordinates), staged(kCoordinates);
    Eigen::ArrayXd nudged = abar;
    nudged[20] *= 1 + nudge;  // (negative control)
    const auto got = iterate_pass(kCoordinates, lanes(d.q), nudged.data(), lanes(d.g[0]),
                                  lanes(d.p), lanes(next), lanes(staged), scale, w.data());
    const bool same = bytes(next) == bytes(expected) &&
                      bytes(staged) == bytes(Eigen::ArrayXcd(scale * expected)) &&
                      got[0] == sums[0] && got[1] == sums[1];
    EXPECT_EQ(same, nudge == 0) << "nudge " << nudge;
  }
}

// The stage's start (start_passes) gives the bits of start_stage's expressions: r_i = phi0c q +
// hcphi1c p - sum_{j<i} abar_ij G_j, Q_0 = r_i - abar_ii guess, its scaled copy and |Q_0|^2, for
// stages i = 0..3.
TEST(ImplicitPasses, StartGivesTheBitsOfEigensExpressions) {
  for (int i = 0; i < 4; ++i)
    for (double nudge : {0.0, 0x1p-40}) {
      SCOPED_TRACE("stage " + std::to_string(i) + ", nudge " + std::to_string(nudge));
      UpdateData<std::complex<double>> d(i + 1, 5u + unsigned(i));  // (g[i]: the guess)
      const Eigen::ArrayXd w = d.phi0m1.abs(), &abar_ii = d.mhMphi1;
      const double scale = 1.0 / 64;
      Eigen::ArrayXcd r = d.phi0m1 * d.q + d.hphi1 * d.p;
      for (int j = 0; j < i; ++j) r -= d.hb[size_t(j)] * d.g[size_t(j)];
      const Eigen::ArrayXcd Q0 = r - abar_ii * d.g[size_t(i)];
      Eigen::ArrayXcd r_got(kCoordinates), Q0_got(kCoordinates), staged(kCoordinates);
      std::vector<Eigen::ArrayXd> hb = d.hb;
      hb[size_t(i)][9] *= 1 + nudge;  // (negative control: abar_ii for i = 0, else abar_i0 too)
      if (i > 0) hb[0][9] *= 1 + nudge;
      const StartTerms t{lanes(d.q),   lanes(d.p),    nullptr,       lanes(d.g[size_t(i)]),
                         lanes(r_got), lanes(Q0_got), lanes(staged), scale,
                         w.data()};
      const Eigen::ArrayXd abar = i == 0 ? Eigen::ArrayXd(abar_ii * (1 + nudge)) : abar_ii;
      const double norm2 = start_passes<const double*>(
          i, kCoordinates, t, d.phi0m1.data(), d.hphi1.data(), abar.data(), [&](int j) {
            return std::pair{lanes(d.g[size_t(j)]),
                             static_cast<const double*>(hb[size_t(j)].data())};
          });
      const bool same = bytes(r_got) == bytes(r) && bytes(Q0_got) == bytes(Q0) &&
                        bytes(staged) == bytes(Eigen::ArrayXcd(scale * Q0)) &&
                        norm2 == (w * Q0.abs2()).sum();
      EXPECT_EQ(same, nudge == 0);
    }
}

// The predictor's pass (predict_pass) gives the bits of its expressions, w_0 g_0 + w_1 g_1 + ...
// summed node after node, for 1 to 8 nodes (unrolled up to 6, a loop beyond), on real and
// complex coordinates. Negative control: one weight times 1 + 2^-40 changes the bits.
template <class Scalar>
void check_predict() {
  for (int nodes = 1; nodes <= 8; ++nodes)
    for (double nudge : {0.0, 0x1p-40}) {
      SCOPED_TRACE("nodes " + std::to_string(nodes) + ", nudge " + std::to_string(nudge));
      UpdateData<Scalar> d(nodes, 11u + unsigned(nodes));
      std::vector<double> w(static_cast<size_t>(nodes));
      for (int l = 0; l < nodes; ++l) w[size_t(l)] = d.hb[size_t(l)][0];
      typename UpdateData<Scalar>::Array expected = w[0] * d.g[0];
      for (int l = 1; l < nodes; ++l) expected += w[size_t(l)] * d.g[size_t(l)];
      std::vector<const double*> g;
      for (auto& x : d.g) g.push_back(lanes(x));
      w[size_t(nodes - 1)] *= 1 + nudge;
      typename UpdateData<Scalar>::Array got(kCoordinates);
      predict_pass<int(sizeof(Scalar) / sizeof(double))>(kCoordinates, g.data(), w.data(), nodes,
                                                         lanes(got));
      EXPECT_EQ(bytes(got) == bytes(expected), nudge == 0);
    }
}

TEST(ImplicitPasses, PredictGivesTheBitsOfEigensExpressions) {
  check_predict<double>();
  check_predict<std::complex<double>>();
}

#ifdef ERKN_AVX_PASSES
// The passes' AVX entry (run_pass takes it on CPUs with AVX) gives the baseline entry's bits,
// on the same random data with a NaN and an infinity among the gradients: the bytes of the
// state, of three output arrays and of what the entry returns. Negative control: one entry of q
// times 1 + 2^-40 changes the bits.
template <class Entry>
std::vector<unsigned char> entry_bytes(Entry entry, double nudge) {
  UpdateData<std::complex<double>> d(2, 3u);
  d.q[9] *= 1 + nudge;
  d.g[0][4] = {std::numeric_limits<double>::quiet_NaN(), 1.0};
  d.g[1][6] = {2.0, std::numeric_limits<double>::infinity()};
  Eigen::ArrayXcd a = Eigen::ArrayXcd::Zero(kCoordinates), b = a, c = a;
  const auto result = entry(d, a, b, c);
  std::vector<unsigned char> out = state_bytes(d);
  for (const auto* x : {&a, &b, &c}) {
    const std::vector<unsigned char> y = bytes(*x);
    out.insert(out.end(), y.begin(), y.end());
  }
  const auto* r = reinterpret_cast<const unsigned char*>(&result);
  out.insert(out.end(), r, r + sizeof(result));
  return out;
}
template <class Baseline, class Avx>
void check_avx_entry(Baseline baseline, Avx avx) {
  EXPECT_EQ(entry_bytes(baseline, 0), entry_bytes(avx, 0));
  EXPECT_NE(entry_bytes(baseline, 0), entry_bytes(avx, 0x1p-40));  // (negative control)
}
using C = const double*;

// The update's first-and-last stage pass and the compensated add.
TEST(ImplicitPasses, AvxEntryGivesTheBaselinesBitsInTheUpdate) {
  const auto update = [](auto entry) {
    return [entry](auto& d, auto& dq, auto& dp, auto&) {
      const UpdateCoefficients<C> k{d.phi0m1.data(), d.hphi1.data(), d.mhMphi1.data()};
      return entry(kCoordinates, lanes(d.q), lanes(d.p), lanes(d.g[0]), lanes(dq), lanes(dp), k,
                   d.h2bbar[0].data(), d.hb[0].data());
    };
  };
  using U = UpdatePass<2, true, true, C>;
  check_avx_entry(update(pass_entry<U, Eigen::Index, double*, double*, double*, double*, double*,
                                    UpdateCoefficients<C>, C, C>),
                  update(pass_entry_avx<U, Eigen::Index, double*, double*, double*, double*,
                                        double*, UpdateCoefficients<C>, C, C>));
  const auto add = [](auto entry) {
    return [entry](auto& d, auto&, auto&, auto&) {
      entry(kCoordinates, lanes(d.q), lanes(d.eq), lanes(d.g[1]));
      return 0;
    };
  };
  using A = AddPass<2, true>;
  check_avx_entry(add(pass_entry<A, Eigen::Index, double*, double*, double*>),
                  add(pass_entry_avx<A, Eigen::Index, double*, double*, double*>));
}

// The fixed point's pass, the stage's start and the predictor's polynomial (three nodes).
TEST(ImplicitPasses, AvxEntryGivesTheBaselinesBitsInTheStage) {
  const auto iterate = [](auto entry) {
    return [entry](auto& d, auto& next, auto& staged, auto&) {
      return entry(kCoordinates, lanes(d.q), d.hphi1.data(), lanes(d.g[0]), lanes(d.p), lanes(next),
                   lanes(staged), 0.25, d.phi0m1.data());
    };
  };
  using I = IteratePass<C>;
  check_avx_entry(
      iterate(
          pass_entry<I, Eigen::Index, double*, C, double*, double*, double*, double*, double, C>),
      iterate(pass_entry_avx<I, Eigen::Index, double*, C, double*, double*, double*, double*,
                             double, C>));
  const auto start = [](auto entry) {
    return [entry](auto& d, auto& r, auto& Q0, auto& staged) {
      const StartTerms t{lanes(d.q), lanes(d.p),    lanes(d.g[0]), lanes(d.g[1]),  lanes(r),
                         lanes(Q0),  lanes(staged), 0.25,          d.phi0m1.data()};
      return entry(kCoordinates, t, d.hphi1.data(), d.mhMphi1.data(), d.hb[0].data(),
                   d.hb[1].data());
    };
  };
  using S = StartPass<true, true, true, C>;
  check_avx_entry(start(pass_entry<S, Eigen::Index, StartTerms, C, C, C, C>),
                  start(pass_entry_avx<S, Eigen::Index, StartTerms, C, C, C, C>));
  const auto predict = [](auto entry) {
    return [entry](auto& d, auto& out, auto&, auto&) {
      const std::array<const double*, 3> g{lanes(d.q), lanes(d.g[0]), lanes(d.g[1])};
      entry(kCoordinates, g.data(), d.hb[0].data(), 3, lanes(out));
      return 0;
    };
  };
  using P = PredictPass<2, 3>;
  using G = const double* const*;
  check_avx_entry(predict(pass_entry<P, Eigen::Index, G, C, int, double*>),
                  predict(pass_entry_avx<P, Eigen::Index, G, C, int, double*>));
}
#endif

}  // namespace
}  // namespace erkn::detail
