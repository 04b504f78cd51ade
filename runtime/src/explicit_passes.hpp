// The explicit stepper's arithmetic (explicit_stepper.hpp): the exact flow of q'' + M q = 0 and
// the kick, per coordinate or on whole fixed-size arrays (flow_update, kick_update), and one pass
// over the arrays of eigen coordinates that kicks, flows, or kicks and then flows (pass): a kick
// followed by the next stage's flow is one pass, not two, over the same arrays.
//
// Compensated summation (Options::compensated_summation) keeps with q and p the low-order parts
// eq, ep that rounding has dropped (the state is q + eq, p + ep): each update adds the rounding
// error of its sums q + dq, p + dp to eq, ep, dq = (cos - 1) q + sinc p for the flow. Where the
// step is a chain of dependent operations on a few values (kFold: a fixed dimension) the errors
// are folded into q and p at the kick, from values known before dp (whose gradient comes last).
// Over arrays, where the passes' memory traffic counts, each update folds them into its own
// increments (dq + eq, dp + ep) and keeps the residuals of the sums: the flow then reads cos - 1
// but not cos, and the kick makes one sum, not two.
#pragma once

#include <Eigen/Core>
#include <bit>
#include <cstdint>
#include <cstring>

#include "stage_checks.hpp"

namespace erkn::detail {

/// The flow of (q, p) with coefficients cos, cos - 1, sin(w tau)/w, -w sin(w tau) (T: a double
/// or a fixed-size array, C: a double or an array of T's size).
template <bool kKahan, bool kFold, class T, class C>
EIGEN_ALWAYS_INLINE void flow_update(const C& cos, const C& cm1, const C& sinc, const C& msinc,
                                     T& q, T& p, T& eq, T& ep) {
  const T q0 = q, p0 = p;
  if constexpr (kKahan && !kFold) {
    const T dq = (cm1 * q0 + sinc * p0) + eq, dp = (msinc * q0 + cm1 * p0) + ep;
    q = q0 + dq, p = p0 + dp;
    eq = (q0 - q) + dq, ep = (p0 - p) + dp;
  } else {
    const T sp = sinc * p0, mq = msinc * q0;
    p = mq + cos * p0;
    q = cos * q0 + sp;
    if constexpr (kKahan) {
      eq += (q0 - q) + (cm1 * q0 + sp);
      ep += (p0 - p) + (mq + cm1 * p0);
    }
  }
}

/// The kick p += dp.
template <bool kKahan, bool kFold, class T>
EIGEN_ALWAYS_INLINE void kick_update(const T& dp, T& q, T& p, T& eq, T& ep) {
  if constexpr (kKahan && kFold) {
    const T q1 = q + eq;
    eq = (q - q1) + eq;
    q = q1;
    const T p1 = p + ep, e1 = (p - p1) + ep;
    p = p1 + dp;
    ep = e1 + ((p1 - p) + dp);
  } else if constexpr (kKahan) {
    const T p0 = p, dpe = dp + ep;
    p = p0 + dpe;
    ep = (p0 - p) + dpe;
  } else {
    p += dp;
  }
}

/// The state's arrays in eigen coordinates as doubles (a complex coordinate: re, im).
struct PassArrays {
  double *q = nullptr, *p = nullptr, *eq = nullptr, *ep = nullptr;
};

/// A flow's coefficients for a pass: C = double (scalar M: one value) or const double* (one per
/// eigen coordinate, shared by its kLanes doubles).
template <class C>
struct PassFlow {
  C cos, cm1, sinc, msinc;
  static double at(double value, Eigen::Index) { return value; }
  static double at(const double* values, Eigen::Index e) { return values[e]; }
};

/// The non-finite bits (nonfinite_bits) of the force a kick read and of the p it wrote, and of
/// kStageBound times the Q a flow staged (0: every |Q| < 2^512, see kStageBound).
struct PassBits {
  std::uint64_t g = 0, p = 0, stage = 0;
};

/// A staged Q with every |Q| < 2^512 (kStageBound Q finite) is a finite stage: its physical values
/// are the staged ones (identity basis) or the outputs of an inverse transform of them, each a
/// sum of products of at most a polynomial in d of them with unit-modulus twiddles (also in FFTW's
/// intermediates, Rader and Bluestein included), far below DBL_MAX ~ 2^1024. Its gradient then
/// needs no scan of the physical Q (checked_gradient's); a larger one is scanned.
inline constexpr double kStageBound = 0x1p512;

/// What a pass does: kick (p -= hd g, g also to `save` with kSave), then flow (its q also to Q,
/// times Q_scale, with kStage), in place or from one copy of the state into another.
struct PassKind {
  bool kick, flow, in_place, save, stage;
};

/// The kLanes doubles of one eigen coordinate as one value (Value), on which the passes' arithmetic
/// runs lane by lane exactly as on single doubles: a double, or (a complex coordinate, re and im)
/// a vector of two in one SIMD register (GCC's vector extension), the coordinate's real flow
/// coefficients broadcast to both lanes. Bits: the non-finite bits (nonfinite_bits) of each lane.
/// (Left to itself GCC vectorised the complex passes across two coordinates, splitting re and im
/// into separate registers and interleaving them back: 31.5 instructions per coordinate for a
/// plain kick and flow at N = 2048, 56 compensated; one coordinate per register: 23 / 36 over
/// all passes, callgrind, sine-Gordon SABA2.)
template <int kLanes>
struct Lane;
template <>
struct Lane<1> {
  using Value = double;
  using Bits = std::uint64_t;
  static Bits nonfinite(Value x) { return nonfinite_bits(x); }
  static std::uint64_t any(Bits b) { return b; }
};
template <>
struct Lane<2> {
  using Value = double __attribute__((vector_size(16)));
  using Bits = std::uint64_t __attribute__((vector_size(16)));
  static Bits nonfinite(Value x) { return std::bit_cast<Bits>(x - x); }
  static std::uint64_t any(Bits b) { return b[0] | b[1]; }
};
/// V at x, and V stored at x (unaligned SIMD loads and stores; as a double: the double).
template <class V>
EIGEN_ALWAYS_INLINE V lane_load(const double* x) {
  V v;
  std::memcpy(&v, x, sizeof(V));
  return v;
}
template <class V>
EIGEN_ALWAYS_INLINE void lane_store(double* x, const V& v) {
  std::memcpy(x, &v, sizeof(V));
}

// The loop of pass(), one eigen coordinate (a Lane's Value) per iteration: every pointer a
// __restrict parameter of a function not inlined (inlined, or with the pointers as locals or
// members, GCC 12 checks them against each other at run time). In place the *_in pointers are
// null and the pass reads through the ones it writes.
template <bool kKahan, PassKind kKind, int kLanes, class C>
[[gnu::noinline]] PassBits pass_loop(Eigen::Index n, const double* __restrict q_in,
                                     const double* __restrict p_in, const double* __restrict eq_in,
                                     const double* __restrict ep_in, double* __restrict q,
                                     double* __restrict p, double* __restrict eq,
                                     double* __restrict ep, double hd, const double* __restrict g,
                                     double* __restrict save, C cos, C cm1, C sinc, C msinc,
                                     double* __restrict Q, double Q_scale) {
  using L = Lane<kLanes>;
  using V = typename L::Value;
  constexpr bool kInPlace = kKind.in_place;
  typename L::Bits g_bits{}, p_bits{}, stage_bits{};
  for (Eigen::Index e = 0; e < n; ++e) {
    const Eigen::Index x = kLanes * e;
    V qx = lane_load<V>((kInPlace ? q : q_in) + x), px = lane_load<V>((kInPlace ? p : p_in) + x);
    V eqx{}, epx{};
    if constexpr (kKahan)
      eqx = lane_load<V>((kInPlace ? eq : eq_in) + x),
      epx = lane_load<V>((kInPlace ? ep : ep_in) + x);
    if constexpr (kKind.kick) {
      const V gx = lane_load<V>(g + x);
      kick_update<kKahan, false>(V(-hd * gx), qx, px, eqx, epx);
      if constexpr (kKind.save) lane_store(save + x, gx);
      g_bits |= L::nonfinite(gx), p_bits |= L::nonfinite(px);
    }
    if constexpr (kKind.flow) {
      using F = PassFlow<C>;
      flow_update<kKahan, false>(F::at(cos, e), F::at(cm1, e), F::at(sinc, e), F::at(msinc, e), qx,
                                 px, eqx, epx);
      if constexpr (kKind.stage) {
        const V Qx = Q_scale * qx;
        lane_store(Q + x, Qx);
        stage_bits |= L::nonfinite(V(kStageBound * Qx));
      }
    }
    if (kKind.flow || !kInPlace) lane_store(q + x, qx);  // (a kick in place leaves q where it is)
    lane_store(p + x, px);
    if (kKahan && (kKind.flow || !kInPlace)) lane_store(eq + x, eqx);
    if (kKahan) lane_store(ep + x, epx);
  }
  return {L::any(g_bits), L::any(p_bits), L::any(stage_bits)};
}

/// One pass over n eigen coordinates (kLanes doubles each) from `from` into `to` (in place: the
/// same arrays) as kKind says; returns the non-finite bits of the force and p a kick read and
/// wrote and of the Q it staged (PassBits). The arithmetic per coordinate is that of the kick
/// followed by that of the flow.
template <bool kKahan, PassKind kKind, int kLanes, class C>
EIGEN_ALWAYS_INLINE PassBits pass(Eigen::Index n, const PassArrays& from, const PassArrays& to,
                                  double hd, const double* g, double* save, const PassFlow<C>& f,
                                  double* Q, double Q_scale) {
  const PassArrays in = kKind.in_place ? PassArrays{} : from;
  return pass_loop<kKahan, kKind, kLanes, C>(n, in.q, in.p, in.eq, in.ep, to.q, to.p, to.eq, to.ep,
                                             hd, g, save, f.cos, f.cm1, f.sinc, f.msinc, Q,
                                             Q_scale);
}

}  // namespace erkn::detail
