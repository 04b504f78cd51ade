// The explicit stepper's arithmetic (explicit_stepper.hpp): the exact flow of q'' + M q = 0 and
// the kick, per coordinate or on whole fixed-size arrays (flow_update, kick_update), and one pass
// over the arrays of eigen coordinates that kicks, flows, or kicks and then flows (pass): a kick
// followed by the next stage's flow is one pass, not two, over the same arrays.
//
// Compensated summation (Options::compensated_summation) keeps with q and p the low-order parts
// eq, ep that rounding has dropped (the state is q + eq, p + ep). Where the step is a chain of
// dependent operations on a few values (a fixed dimension: flow_update, kick_update) each update
// adds the rounding error of its sums q + dq, p + dp to eq, ep, dq = (cos - 1) q + sinc p for the
// flow, and the errors are folded into q and p at the kick, from values known before dp (whose
// gradient comes last). Over arrays, where the passes' memory traffic counts, the state stays as
// it was at the step's start while the passes accumulate the step's increments dq, dp in plain
// arithmetic (increment form: flow_increment, kicks add to dp); the step's last pass adds them
// to the state in one compensated sum (fold_increment), eq and ep with them. An increment is
// O(h) of the state, and so is the rounding of its sums; the sum q + dq, whose rounding is not,
// is compensated. A pass then reads and writes two arrays of increments besides the state it
// reads, where compensating every pass's sums read and wrote four (and cost ~2.4 times the extra
// instructions over plain passes; explicit_stepper.hpp).
#pragma once

#include <Eigen/Core>
#include <bit>
#include <cstdint>
#include <cstring>

#include "stage_checks.hpp"

namespace erkn::detail {

/// The flow of (q, p) with coefficients c = cos (compensated: cos - 1), sin(w tau)/w,
/// -w sin(w tau) (T: a double or a fixed-size array, C: a double or an array of T's size).
template <bool kKahan, class T, class C>
EIGEN_ALWAYS_INLINE void flow_update(const C& c, const C& sinc, const C& msinc, T& q, T& p, T& eq,
                                     T& ep) {
  C cos = c, cm1 = c;
  if constexpr (kKahan) cos = cm1 + 1.0;  // (FlowCoefficients' plain cosine, bit for bit)
  const T q0 = q, p0 = p;
  const T sp = sinc * p0, mq = msinc * q0;
  p = mq + cos * p0;
  q = cos * q0 + sp;
  if constexpr (kKahan) {
    eq += (q0 - q) + (cm1 * q0 + sp);
    ep += (p0 - p) + (mq + cm1 * p0);
  }
}

/// The kick p += dp.
template <bool kKahan, class T>
EIGEN_ALWAYS_INLINE void kick_update(const T& dp, T& q, T& p, T& eq, T& ep) {
  if constexpr (kKahan) {
    const T q1 = q + eq;
    eq = (q - q1) + eq;
    q = q1;
    const T p1 = p + ep, e1 = (p - p1) + ep;
    p = p1 + dp;
    ep = e1 + ((p1 - p) + dp);
  } else {
    p += dp;
  }
}

/// a + b, or b when a, an increment not made yet in this step (0), is absent (kHave false).
template <bool kHave, class V>
EIGEN_ALWAYS_INLINE V plus(const V& a, const V& b) {
  if constexpr (kHave)
    return a + b;
  else
    return b;
}

/// Increment form: the flow's increments (cos - 1) q + sinc p and -w sin(w tau) q + (cos - 1) p
/// at q = qn + dq, p = pn + dp (qn, pn: the state at the step's start) added to dq, dp.
template <bool kHaveQ, bool kHaveP, class V>
EIGEN_ALWAYS_INLINE void flow_increment(double cm1, double sinc, double msinc, const V& qn,
                                        const V& pn, V& dq, V& dp) {
  const V q = plus<kHaveQ>(dq, qn), p = plus<kHaveP>(dp, pn);
  dq = plus<kHaveQ>(dq, cm1 * q + sinc * p);
  dp = plus<kHaveP>(dp, msinc * q + cm1 * p);
}

/// Increment form, a step's end: x = x0 + (dx + ex0) compensated (Kahan), its rounding error
/// into ex (dx: the step's increment, absent when !kHave).
template <bool kHave, class V>
EIGEN_ALWAYS_INLINE void fold_increment(const V& x0, const V& ex0, const V& dx, V& x, V& ex) {
  const V a = plus<kHave>(dx, ex0);
  x = x0 + a;
  ex = (x0 - x) + a;
}

/// The state's arrays in eigen coordinates as doubles (a complex coordinate: re, im).
struct PassArrays {
  double *q = nullptr, *p = nullptr, *eq = nullptr, *ep = nullptr;
};

/// A flow's coefficients for a pass: C = double (scalar M: one value) or const double* (one per
/// eigen coordinate, shared by its kLanes doubles); c is cos (compensated: cos - 1).
template <class C>
struct PassFlow {
  C c, sinc, msinc;
  static double at(double value, Eigen::Index) { return value; }
  static double at(const double* values, Eigen::Index e) { return values[e]; }
};

/// A staged Q with every |Q| < 2^512 (kStageBound Q finite) is a finite stage: its physical values
/// are the staged ones (identity basis) or the outputs of an inverse transform of them, each a
/// sum of products of at most a polynomial in d of them with unit-modulus twiddles (also in FFTW's
/// intermediates, Rader and Bluestein included), far below DBL_MAX ~ 2^1024. Its gradient then
/// needs no scan of the physical Q (checked_gradient's); a larger one is scanned.
inline constexpr double kStageBound = 0x1p512;

/// What a pass does: kick (p -= hd g, g also to `save` with kSave), then flow (its q also to Q,
/// times Q_scale, with kStage; after fold_q the folded q), in place or from one copy of the state
/// into another; compensated, in increment form, the step's first pass is the one not in place,
/// and fold_q, fold_p add the step's increments of q (after its last flow) and of p (its last
/// pass) to the state. read (get_state's pass, a flow) stores no state: q and p (compensated:
/// folded, q + eq and p + ep) times Q_scale go to Q and p, the inputs of their inverse transforms.
/// check (a step's last pass): its check (pass) covers the p it wrote and a flow's q; with
/// bound_p also |p| < kPBound. backward: the flow over -tau (cos(w tau), -sin(w tau)/w,
/// w sin(w tau)). over_start (the step's first pass, not in place): `to` is the start itself, each
/// coordinate read before it is written (explicit_stepper.hpp, in_place_steps).
struct PassKind {
  bool kick, flow, in_place, save, stage, fold_q, fold_p, read, check = false, backward = false,
                                                                bound_p = false, over_start = false;
};

/// A step that overwrites its start (over_start) is taken only where it cannot fail, so that a
/// step that fails still leaves the state before it: the start with |p| < kPBound = 2^600 and a
/// staged Q below kStageBound (so |q| < kStageBound / Q_scale <= 2^552 for Q_scale >= 2^-40), the
/// force with |hd g| < kPBound (force_bounded), the flow's coefficients at most kFlowBound in
/// modulus. Every value the pass makes is then below 2^667 (p - hd g below 2^601; a flow's
/// c q + sinc p, msinc q + c p and compensated increments below 2^(64 + 602)), finite, and its
/// check can only find a state too large for the next step to be in place, never a failure.
inline constexpr double kPBound = 0x1p600;
inline constexpr double kPScale = 0x1p424;  // (kPScale x overflows where |x| >= kPBound)
inline constexpr double kFlowBound = 0x1p64;

/// Whether every |hd g_j| < kPBound (kLanes n doubles at g): the force of an in-place step.
inline bool force_bounded(Eigen::Index n, const double* __restrict g, double hd) {
  const double scaled = kPScale * hd;
  std::uint64_t bits = 0;
  for (Eigen::Index j = 0; j < n; ++j) bits |= nonfinite_bits(scaled * g[j]);
  return bits == 0;
}

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

// What get_state's inverse transform reads of a coordinate, Q_scale (x + ex), stored to out + j:
// compensated, x, ex the ones fold_increment makes from x0, ex0 (at + j) and the increment dx;
// plain, x = dx, the coordinate itself, and ex = 0. x and ex themselves are not stored.
template <bool kKahan, bool kHave, class V>
EIGEN_ALWAYS_INLINE void store_read(const double* x0, const double* ex0, Eigen::Index j,
                                    const V& dx, double Q_scale, double* out) {
  if constexpr (kKahan) {
    V x, ex;
    fold_increment<kHave>(lane_load<V>(x0 + j), lane_load<V>(ex0 + j), dx, x, ex);
    lane_store(out + j, V(Q_scale * (x + ex)));
  } else {
    lane_store(out + j, V(Q_scale * dx));
  }
}

// fold_increment of the coordinate at x0, ex0 (the state at the step's start and its error) with
// the increment dx, which becomes the new x; the new error is stored to ex. Returns the new x.
template <bool kHave, class V>
EIGEN_ALWAYS_INLINE V fold_at(const double* x0, const double* ex0, double* ex, V& dx) {
  V e;
  fold_increment<kHave>(lane_load<V>(x0), lane_load<V>(ex0), dx, dx, e);
  lane_store(ex, e);
  return dx;
}

// The flow of coordinate e (its doubles at x) in a pass, coefficients f (compensated: cos - 1):
// plain, of the state (qx, px); compensated, in increment form, of the state at the step's start
// (qn, pn at q_in + x, p_in + x) plus its increments (qx, px; absent before they are made: kHaveQ,
// kHaveP), the flow's increments added to them. Returns the stage's q: the flowed q (compensated:
// qn + qx). (The loads come before the coefficients' as in the loop it came from: GCC orders and
// allocates the registers differently the other way round.)
template <bool kKahan, bool kHaveQ, bool kHaveP, bool kBackward, class V, class C>
EIGEN_ALWAYS_INLINE V flow_at(const PassFlow<C>& f, Eigen::Index e, const double* q_in,
                              const double* p_in, Eigen::Index x, V& qx, V& px) {
  using F = PassFlow<C>;
  // (over -tau: the sines negated, exactly)
  const double sinc = kBackward ? -F::at(f.sinc, e) : F::at(f.sinc, e);
  const double msinc = kBackward ? -F::at(f.msinc, e) : F::at(f.msinc, e);
  if constexpr (kKahan) {
    const V qn = lane_load<V>(q_in + x), pn = lane_load<V>(p_in + x);
    flow_increment<kHaveQ, kHaveP>(F::at(f.c, e), sinc, msinc, qn, pn, qx, px);
    return qn + qx;
  } else {
    V unused{};
    flow_update<false>(F::at(f.c, e), sinc, msinc, qx, px, unused, unused);
    return qx;
  }
}

// A coordinate's stage and check (see pass) after a pass's arithmetic: with a flow that stages,
// Q_scale Qx to Q + x and the bits of its bound (with check, also p's; bound_p: |p| < kPBound);
// else with check the bits of p + q after a flow, or of p; else none.
template <PassKind kKind, class L, class V>
EIGEN_ALWAYS_INLINE typename L::Bits stage_and_check(V Qx, const V& qx, const V& px, double Q_scale,
                                                     double* Q, Eigen::Index x) {
  if constexpr (kKind.flow && kKind.stage) {
    Qx = Q_scale * Qx;
    lane_store(Q + x, Qx);
    const V bound = kStageBound * Qx;
    const V p_check = kKind.bound_p ? V(kPScale * px) : px;
    return L::nonfinite(kKind.check ? V(p_check + bound) : bound);
  } else if constexpr (kKind.check) {
    return L::nonfinite(kKind.flow ? V(px + qx) : px);
  } else {
    return typename L::Bits{};
  }
}

// The loop of pass(), one eigen coordinate (a Lane's Value) per iteration: every pointer a
// __restrict parameter (its pointers as locals or members, GCC 12 checks them against each other
// at run time), inlined into one of the noinline entries below only. Plain, in place, the *_in
// pointers are null and the pass reads through the ones it writes. Compensated (increment form) q
// and p are the step's increments dq, dp (absent, 0, before its first pass, the one not in place),
// *_in the state at its start, read by every pass; fold_q puts the new q, eq in q, eq (and
// stages the new q, as the stepper's unstaged path reads it), fold_p the new p, ep in p, ep.
template <bool kKahan, PassKind kKind, int kLanes, class C>
EIGEN_ALWAYS_INLINE bool pass_body(Eigen::Index n, const double* __restrict q_in,
                                   const double* __restrict p_in, const double* __restrict eq_in,
                                   const double* __restrict ep_in, double* __restrict q,
                                   double* __restrict p, double* __restrict eq,
                                   double* __restrict ep, double hd, const double* __restrict g,
                                   double* __restrict save, C c, C sinc, C msinc,
                                   double* __restrict Q, double Q_scale) {
  using L = Lane<kLanes>;
  using V = typename L::Value;
  constexpr bool kInPlace = kKind.in_place;
  constexpr bool kFoldQ = kKahan && kKind.fold_q, kFoldP = kKahan && kKind.fold_p;
  // (compensated: whether dq, dp have been made, before the flow and after it)
  constexpr bool kHadP = !kKahan || kInPlace;  // (p read: plain, or an increment made)
  constexpr bool kHaveQ = kInPlace, kHaveP = kInPlace || kKind.kick;
  constexpr bool kMadeQ = kHaveQ || kKind.flow, kMadeP = kHaveP || kKind.flow;
  // The pass's check (see pass): one value per coordinate whose finiteness implies what the step
  // needs to know, a non-finite force included (a kick's p - hd g is then non-finite, and so is
  // every q or p a flow makes of it: a finite coefficient times an infinity or a NaN is not
  // finite, 0 times one is a NaN).
  constexpr bool kStageQ = kKind.flow && kKind.stage;
  constexpr bool kCheckG = kKind.kick && !kStageQ && !kKind.check;
  static_assert(!kKind.bound_p || (kStageQ && kKind.check), "bound_p: a step's last, staging pass");
  // The step's start (over_start: `to` itself, each coordinate read before it is written).
  const double* const qs = kKind.over_start ? q : q_in;
  const double* const ps = kKind.over_start ? p : p_in;
  const double* const eqs = kKind.over_start ? eq : eq_in;
  const double* const eps = kKind.over_start ? ep : ep_in;
  typename L::Bits bits{};
  for (Eigen::Index e = 0; e < n; ++e) {
    const Eigen::Index x = kLanes * e;
    V qx{}, px{};  // (plain: the state; compensated: the increments)
    if (!kKahan || kInPlace)
      qx = lane_load<V>((kInPlace ? q : qs) + x), px = lane_load<V>((kInPlace ? p : ps) + x);
    if constexpr (kKind.kick) {
      const V gx = lane_load<V>(g + x);
      px = plus<kHadP>(px, V(-hd * gx));
      if constexpr (kKind.save) lane_store(save + x, gx);
      if constexpr (kCheckG) bits |= L::nonfinite(gx);
    }
    V Qx{};  // (the stage's q)
    if constexpr (kKind.flow)
      Qx = flow_at<kKahan, kHaveQ, kHaveP, kKind.backward>(PassFlow<C>{c, sinc, msinc}, e, qs, ps,
                                                           x, qx, px);
    if constexpr (kKind.read) {  // (get_state's pass: q to Q, p to p, no state stored)
      store_read<kKahan, kMadeQ>(qs, eqs, x, qx, Q_scale, Q);
      store_read<kKahan, kMadeP>(ps, eps, x, px, Q_scale, p);
      continue;
    }
    if constexpr (kFoldQ) Qx = fold_at<kMadeQ>(qs + x, eqs + x, eq + x, qx);
    if constexpr (kFoldP) fold_at<kMadeP>(ps + x, eps + x, ep + x, px);
    bits |= stage_and_check<kKind, L>(Qx, qx, px, Q_scale, Q, x);
    if (kKind.flow || !kInPlace || kFoldQ) lane_store(q + x, qx);  // (a kick in place: q stays)
    lane_store(p + x, px);
  }
  return L::any(bits) != 0;
}

// pass_body as a function of its own, for the baseline instruction set (pass_loop) and, on x86-64
// CPUs with AVX, VEX-encoded (pass_loop_avx; kAvxPasses: cpuid, once at load). The same IEEE
// operations lane by lane in the same order, only encoded with three operands, memory operands
// and vmovddup: no register copies, separate loads or broadcasts. Target avx, not fma: GCC
// contracts a * b + c into an FMA where it can (with fma, 81 of the 84 passes of
// ExplicitPasses.AvxEntryGivesTheBaselinesBits change their bits; with avx none does).
// callgrind, sine-Gordon N = 512, SABA2, construct + integrate of 40 steps: 5.73M -> 5.61M
// instructions compensation off, 6.09M -> 5.69M on (the compensated kick-and-flow pass 47 -> 40
// per coordinate). erkn_integrate_benchmark --short, sine-Gordon scenes, 2 runs of each build
// alternated (load 8-14), per cell the median: defaults <= 1.05 at N >= 512 in 76 -> 101 of 112
// cells (callback and compiled rows); compensation's cost (defaults over compensation off, median
// over the methods) N = 512 1.046 -> 1.040, 2048 1.042 -> 1.034, 8192 1.043 -> 1.034 (callback),
// and compensation off 0-2 % faster. The passes at N >= 512 read more than L1 holds (callgrind's
// cache model, SABA2 N = 512: compensation adds ~16k L1 read misses to a run, its eq and ep in
// two copies), so their time falls less than their instructions.
template <bool kKahan, PassKind kKind, int kLanes, class C, class... A>
[[gnu::noinline]] bool pass_loop(A... a) {
  return pass_body<kKahan, kKind, kLanes, C>(a...);
}
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && !defined(__AVX__)
#define ERKN_AVX_PASSES 1
template <bool kKahan, PassKind kKind, int kLanes, class C, class... A>
[[gnu::noinline, gnu::target("avx")]] bool pass_loop_avx(A... a) {
  return pass_body<kKahan, kKind, kLanes, C>(a...);
}
inline const bool kAvxPasses = [] {
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx") != 0;
}();
#endif

/// One pass over n eigen coordinates (kLanes doubles each) from `from` into `to` (in place: the
/// same arrays; compensated, from the state at the step's start and the increments in `to`) as
/// kKind says. The arithmetic per coordinate is that of the kick followed by that of the flow (and
/// the fold). Returns false when every entry passed the pass's check, a test that needs no exact
/// answer (the caller then scans what it needs: a slow path): a staged Q with every |Q| below
/// kStageBound (then also the force finite); check (a step's last pass), p and q finite, and a
/// staged Q bounded (the sum p + kStageBound Q, or p + q, finite); else a kick's force finite.
/// (One flag in a register, where three 64-bit words of bits came back through memory and a step
/// reloading two of them as one 16-byte word waited for the pass's two stores, not forwarded:
/// ~30 % of the step's own time at sine-Gordon N = 32, perf, Intel Xeon. One check value per
/// coordinate, where the force, p and the bound were three: the checks were 7 of the ~15 vector
/// operations per coordinate of the last pass of Strang, which bound its time.)
template <bool kKahan, PassKind kKind, int kLanes, class C>
EIGEN_ALWAYS_INLINE bool pass(Eigen::Index n, const PassArrays& from, const PassArrays& to,
                              double hd, const double* g, double* save, const PassFlow<C>& f,
                              double* Q, double Q_scale) {
  const PassArrays in = (kKind.in_place && !kKahan) || kKind.over_start ? PassArrays{} : from;
#ifdef ERKN_AVX_PASSES
  if (kAvxPasses)
    return pass_loop_avx<kKahan, kKind, kLanes, C>(n, in.q, in.p, in.eq, in.ep, to.q, to.p, to.eq,
                                                   to.ep, hd, g, save, f.c, f.sinc, f.msinc, Q,
                                                   Q_scale);
#endif
  return pass_loop<kKahan, kKind, kLanes, C>(n, in.q, in.p, in.eq, in.ep, to.q, to.p, to.eq, to.ep,
                                             hd, g, save, f.c, f.sinc, f.msinc, Q, Q_scale);
}

}  // namespace erkn::detail
