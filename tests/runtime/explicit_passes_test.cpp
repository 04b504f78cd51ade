// The explicit passes' AVX entry (explicit_passes.hpp: pass_loop_avx, which the stepper takes on
// CPUs with AVX) computes the bits of the baseline entry (pass_loop): every kind of pass, plain
// and compensated, in place and from one copy into another, on real and complex coordinates with
// one flow coefficient or one per coordinate, on random data with non-finite entries.
#include "explicit_passes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

namespace erkn::detail {
namespace {

#ifdef ERKN_AVX_PASSES

constexpr Eigen::Index kCoordinates = 37;  // (odd: no pair of coordinates is special)

/// Every array a pass reads or writes, filled from one seed; the flow coefficients times 1 + nudge.
struct Buffers {
  Buffers(int lanes, double nudge) {
    std::mt19937_64 rng(20261127);
    std::uniform_real_distribution<double> u(-2, 2);
    for (std::vector<double>* x : arrays()) {
      x->resize(size_t(lanes * kCoordinates));
      for (double& y : *x) y = u(rng);
    }
    for (std::vector<double>* x : {&cos, &cm1, &sinc, &msinc}) {
      x->resize(size_t(kCoordinates));
      for (double& y : *x) y = u(rng) * (1 + nudge);
    }
    g[5] = std::numeric_limits<double>::infinity();
    p_in[7] = std::numeric_limits<double>::quiet_NaN();
  }
  std::vector<std::vector<double>*> arrays() {
    return {&q_in, &p_in, &eq_in, &ep_in, &q, &p, &eq, &ep, &g, &save, &Q};
  }
  std::vector<double> q_in, p_in, eq_in, ep_in, q, p, eq, ep, g, save, Q, cos, cm1, sinc, msinc;
};

/// The bytes of every array after the pass (baseline or AVX entry), and its check.
template <bool kKahan, PassKind kKind, int kLanes, class C>
std::vector<unsigned char> outcome(bool avx, double nudge) {
  Buffers b(kLanes, nudge);
  auto coefficient = [](const std::vector<double>& x) {
    if constexpr (std::is_same_v<C, double>)
      return x[0];
    else
      return x.data();
  };
  // (the cosine a pass reads: cos, compensated cos - 1)
  const C c = coefficient(kKahan ? b.cm1 : b.cos), s = coefficient(b.sinc),
          ms = coefficient(b.msinc);
  const auto run = [&](auto entry) {
    return entry(kCoordinates, b.q_in.data(), b.p_in.data(), b.eq_in.data(), b.ep_in.data(),
                 b.q.data(), b.p.data(), b.eq.data(), b.ep.data(), 0.37 * (1 + nudge), b.g.data(),
                 b.save.data(), c, s, ms, b.Q.data(), 0.25);
  };
  const bool check =
      avx ? run([](auto... a) { return pass_loop_avx<kKahan, kKind, kLanes, C>(a...); })
          : run([](auto... a) { return pass_loop<kKahan, kKind, kLanes, C>(a...); });
  std::vector<unsigned char> bytes;
  auto append = [&](const void* x, size_t n) {
    const auto* y = static_cast<const unsigned char*>(x);
    bytes.insert(bytes.end(), y, y + n);
  };
  for (std::vector<double>* x : b.arrays()) append(x->data(), x->size() * sizeof(double));
  append(&check, sizeof check);
  return bytes;
}

// The pass kinds {kick, flow, in place, save, stage, fold q, fold p, read, check, backward} the
// stepper makes, each also with in_place flipped.
constexpr PassKind kKinds[] = {
    {false, true, false, false, true, false, false, false},              // a step's first flow
    {false, true, false, false, false, true, true, false, false, true},  // get_state's flow back
    {false, true, false, false, false, true, true, true, false, true},   // ... reading out
    {true, false, true, false, false, false, false, false},              // a kick
    {true, false, true, true, false, false, true, false, true},          // the last kick (FSAL)
    {true, true, true, false, true, false, false, false},                // a kick and a flow
    {true, true, true, false, true, true, false, false},                 // ... folding q
    {true, true, true, false, false, false, false, false},               // ... not staged
    {true, true, true, false, true, false, true, false, true},           // the last, ahead
    {true, true, true, false, false, false, true, false, true},          // ... not staged
};
constexpr PassKind flipped(PassKind k) {
  k.in_place = !k.in_place;
  return k;
}

/// Outcomes that differ between the entries over every kind (nudge: the AVX entry's kick weight
/// and flow coefficients scaled by 1 + nudge).
template <bool kKahan, int kLanes, class C, size_t... k>
int differences(double nudge, std::index_sequence<k...>) {
  auto one = [&](auto kind) {
    constexpr PassKind K = decltype(kind)::value;
    return int(outcome<kKahan, K, kLanes, C>(false, 0) !=
               outcome<kKahan, K, kLanes, C>(true, nudge));
  };
  return (0 + ... +
          (one(std::integral_constant<PassKind, kKinds[k]>{}) +
           one(std::integral_constant<PassKind, flipped(kKinds[k])>{})));
}
template <bool kKahan, int kLanes, class C>
int differences(double nudge) {
  return differences<kKahan, kLanes, C>(nudge, std::make_index_sequence<std::size(kKinds)>{});
}
int all_differences(double nudge) {
  return differences<false, 1, double>(nudge) + differences<true, 1, double>(nudge) +
         differences<false, 1, const double*>(nudge) + differences<true, 1, const double*>(nudge) +
         differences<false, 2, const double*>(nudge) + differences<true, 2, const double*>(nudge);
}

TEST(ExplicitPasses, AvxEntryGivesTheBaselinesBits) {
  if (!kAvxPasses) GTEST_SKIP() << "this CPU has no AVX";
  EXPECT_EQ(all_differences(0), 0);
  // Negative control: the kick weight and flow coefficients 2^-40 apart change every one of the
  // 120 passes' outcomes.
  EXPECT_EQ(all_differences(0x1p-40), 6 * 2 * int(std::size(kKinds)));
}

#endif

}  // namespace
}  // namespace erkn::detail
