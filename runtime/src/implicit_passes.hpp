// The implicit step's passes over arrays of eigen coordinates (stepper.hpp, a dynamic dimension):
// the fixed point's iterate on the half spectrum (iterate_pass, below) and eq. (d)'s update from
// the solved stages' gradients g_i,
//   dq = (phi0(V) - 1) q + h phi1(V) p - h^2 sum_i bbar_i(V) g_i
//   dp = -h M phi1(V) q + (phi0(V) - 1) p - h sum_i b_i(V) g_i,
// then q += dq, p += dp (compensated_sum.hpp): the arithmetic written once (update_start,
// update_stage: on whole fixed-size arrays, or on one eigen coordinate), over arrays one pass per
// stage (the first also forms the q and p terms, the last takes the non-finite bits of q + dq and
// p + dp the step checks) and one pass that adds, each coordinate's kLanes doubles one value
// (explicit_passes.hpp's Lane). The same IEEE operations per double in the same order as Eigen's
// expressions, which made 2 s + 6 passes (two finiteness checks, the compensated sum's four):
// callgrind, sine-Gordon N = 32 (h = 1/40, 400 steps), 20 runs of construct + integrate in one
// process (start-up included), instructions per grad U
// SERKN2s3 7,664 -> 7,332, SERKN1s2(1) 7,355 -> 6,933, RKN2s3 6,771 -> 6,489.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <type_traits>

#include "compensated_sum.hpp"
#include "explicit_passes.hpp"

namespace erkn::detail {

/// dq = phi0m1 q + hphi1 p, dp = mhMphi1 q + phi0m1 p (before the stages' terms).
template <class C, class X, class T>
EIGEN_ALWAYS_INLINE void update_start(const C& phi0m1, const C& hphi1, const C& mhMphi1, const X& q,
                                      const X& p, T& dq, T& dp) {
  dq = phi0m1 * q + hphi1 * p;
  dp = mhMphi1 * q + phi0m1 * p;
}
/// Stage i's terms: dq -= h^2 bbar_i g_i, dp -= h b_i g_i.
template <class C, class T, class G>
EIGEN_ALWAYS_INLINE void update_stage(const C& h2bbar, const C& hb, const G& g, T& dq, T& dp) {
  dq -= h2bbar * g;
  dp -= hb * g;
}

/// A coefficient of a pass at eigen coordinate e: one number, or one per coordinate.
inline double coefficient_at(double value, Eigen::Index) { return value; }
inline double coefficient_at(const double* values, Eigen::Index e) { return values[e]; }

/// The update's coefficients for a pass: C = double (one eigenvalue) or const double* (one per
/// eigen coordinate, shared by its kLanes doubles).
template <class C>
struct UpdateCoefficients {
  C phi0m1, hphi1, mhMphi1;
};

/// The non-finite bits of q + dq and of p + dp (0: finite), taken by the last stage's pass.
struct UpdateBits {
  std::uint64_t q = 0, p = 0;
};

// Each pass's loop is a Body::run, always inlined into one of two entries (run_pass), as
// explicit_passes.hpp's passes are: the baseline one and, on x86-64 CPUs with AVX, a VEX-encoded
// copy (kAvxPasses): the same IEEE operations in the same order, without register copies and with
// vmovddup broadcasts of the coefficients (not fma: GCC would contract). callgrind, sine-Gordon
// N = 32, instructions per grad U: SERKN2s3 6,862 -> 6,597, SERKN1s2(1) 6,465 -> 6,238.
template <class Body, class... A>
[[gnu::noinline]] auto pass_entry(A... a) {
  return Body::run(a...);
}
#ifdef ERKN_AVX_PASSES
template <class Body, class... A>
[[gnu::noinline, gnu::target("avx")]] auto pass_entry_avx(A... a) {
  return Body::run(a...);
}
#endif
template <class Body, class... A>
EIGEN_ALWAYS_INLINE auto run_pass(A... a) {
#ifdef ERKN_AVX_PASSES
  if (kAvxPasses) return pass_entry_avx<Body>(a...);
#endif
  return pass_entry<Body>(a...);
}

// One stage's pass over n eigen coordinates: stage i's terms (g, h2bbar, hb) added to dq, dp,
// which the first pass (kFirst) starts from q and p; the last (kLast) returns the non-finite bits
// of q + dq, p + dp. Every pointer a __restrict parameter (pass_body's reason).
template <int kLanes, bool kFirst, bool kLast, class C>
struct UpdatePass {
  static EIGEN_ALWAYS_INLINE UpdateBits run(Eigen::Index n, const double* __restrict q,
                                            const double* __restrict p, const double* __restrict g,
                                            double* __restrict dq, double* __restrict dp,
                                            UpdateCoefficients<C> k, C h2bbar, C hb) {
    using L = Lane<kLanes>;
    using V = typename L::Value;
    typename L::Bits q_bits{}, p_bits{};
    for (Eigen::Index e = 0; e < n; ++e) {
      const Eigen::Index x = kLanes * e;
      V a, b;
      if constexpr (kFirst)
        update_start(coefficient_at(k.phi0m1, e), coefficient_at(k.hphi1, e),
                     coefficient_at(k.mhMphi1, e), lane_load<V>(q + x), lane_load<V>(p + x), a, b);
      else
        a = lane_load<V>(dq + x), b = lane_load<V>(dp + x);
      update_stage(coefficient_at(h2bbar, e), coefficient_at(hb, e), lane_load<V>(g + x), a, b);
      if constexpr (kLast) {
        q_bits |= L::nonfinite(lane_load<V>(q + x) + a);
        p_bits |= L::nonfinite(lane_load<V>(p + x) + b);
      }
      lane_store(dq + x, a);
      lane_store(dp + x, b);
    }
    return {L::any(q_bits), L::any(p_bits)};
  }
};

/// x += dx over n eigen coordinates, compensated (kKahan: error carries x's lost low-order
/// bits; dx is clobbered) or plain.
template <int kLanes, bool kKahan>
struct AddPass {
  static EIGEN_ALWAYS_INLINE void run(Eigen::Index n, double* __restrict x,
                                      double* __restrict error, double* __restrict dx) {
    using V = typename Lane<kLanes>::Value;
    for (Eigen::Index e = 0; e < n; ++e) {
      const Eigen::Index j = kLanes * e;
      V xv = lane_load<V>(x + j), dv = lane_load<V>(dx + j);
      if constexpr (kKahan) {
        V ev = lane_load<V>(error + j);
        compensated_add(xv, ev, dv);
        lane_store(error + j, ev);
      } else {
        xv += dv;
      }
      lane_store(x + j, xv);
    }
  }
};
template <int kLanes, bool kKahan>
void add_pass(Eigen::Index n, double* x, double* error, double* dx) {
  run_pass<AddPass<kLanes, kKahan>>(n, x, error, dx);
}

/// The stages' passes of the update: dq, dp from q, p and the gradients g[i] (i < s) with stage
/// i's coefficients h2bbar(i), hb(i); returns the non-finite bits of q + dq, p + dp.
template <int kLanes, class C, class Stage>
UpdateBits update_passes(int s, Eigen::Index n, const double* q, const double* p, double* dq,
                         double* dp, const UpdateCoefficients<C>& k, Stage&& stage) {
  const auto run = [&](auto first, auto last, int i) {
    const auto [g, h2bbar, hb] = stage(i);
    return run_pass<UpdatePass<kLanes, first.value, last.value, C>>(n, q, p, g, dq, dp, k, h2bbar,
                                                                    hb);
  };
  using T = std::true_type;
  using F = std::false_type;
  if (s == 1) return run(T{}, T{}, 0);
  run(T{}, F{}, 0);
  for (int i = 1; i + 1 < s; ++i) run(F{}, F{}, i);
  return run(F{}, T{}, s - 1);
}

/// A fixed-point iteration's pass over n complex eigen coordinates (stage_fixed_point.hpp, a
/// transform with a staging buffer): Q_new = r - abar g, staged = scale Q_new (the inverse
/// transform's input, staging_scale()), and {sum_e w_e |Q_new - Q|_e^2, sum_e w_e |Q_new|_e^2}
/// summed one coordinate after the other from the first, as squared_norm's Eigen expression sums
/// them (the same bits). In Eigen's expressions they were three passes and the inverse
/// transform's scaled copy a fourth.
template <class C>
struct IteratePass {
  static EIGEN_ALWAYS_INLINE Lane<2>::Value run(Eigen::Index n, const double* __restrict r, C abar,
                                                const double* __restrict g,
                                                const double* __restrict Q,
                                                double* __restrict Q_new, double* __restrict staged,
                                                double scale, const double* __restrict w) {
    using V = Lane<2>::Value;
    using I = std::int64_t __attribute__((vector_size(16)));
    V sums{};  // {X, N} (one register, returned as it is: GCC kept two doubles on the stack)
    for (Eigen::Index e = 0; e < n; ++e) {
      const Eigen::Index x = 2 * e;
      const V next = lane_load<V>(r + x) - coefficient_at(abar, e) * lane_load<V>(g + x);
      const V change = next - lane_load<V>(Q + x);
      const V c2 = change * change, n2 = next * next;
      // {re^2 of the change, of next} + {im^2 of the change, of next}: abs2 = re^2 + im^2
      sums += w[e] * (__builtin_shuffle(c2, n2, I{0, 2}) + __builtin_shuffle(c2, n2, I{1, 3}));
      lane_store(Q_new + x, next);
      lane_store(staged + x, V(scale * next));
    }
    return sums;
  }
};
template <class C>
Lane<2>::Value iterate_pass(Eigen::Index n, const double* r, C abar, const double* g,
                            const double* Q, double* Q_new, double* staged, double scale,
                            const double* w) {
  return run_pass<IteratePass<C>>(n, r, abar, g, Q, Q_new, staged, scale, w);
}

/// The stage's start on the half spectrum (stage_solver.hpp's start_stage, a transform with a
/// staging buffer), one pass per term of r_i = phi0c q + hcphi1c p - sum_{j<i} abar_ij G_j: the
/// first (kFromState) forms phi0c q + hcphi1c p, each with kTerm subtracts one abar_ij G_j (in j's
/// order), and the last (kFinal) also forms Q_0 = r_i - abar_ii guess, stages scale Q_0 and
/// returns sum_e w_e |Q_0|_e^2 (squared_norm's order; 0 before the last). Eigen's expressions
/// made i + 3 passes and the inverse transform's scaled copy one more.
struct StartTerms {
  const double *q, *p, *G, *guess;
  double *r, *Q0, *staged;
  double scale;
  const double* w;
};
template <bool kFromState, bool kTerm, bool kFinal, class C>
struct StartPass {
  static EIGEN_ALWAYS_INLINE double run(Eigen::Index n, StartTerms t, C phi0c, C hcphi1c, C abar_ij,
                                        C abar_ii) {
    using V = Lane<2>::Value;
    const double* __restrict q = t.q, * __restrict p = t.p, * __restrict G = t.G, * __restrict guess = t.guess, * __restrict w = t.w;
    double* __restrict r = t.r, * __restrict Q0 = t.Q0, * __restrict staged = t.staged;
    double norm2 = 0;
    for (Eigen::Index e = 0; e < n; ++e) {
      const Eigen::Index x = 2 * e;
      V rx;
      if constexpr (kFromState)
        rx = coefficient_at(phi0c, e) * lane_load<V>(q + x) +
             coefficient_at(hcphi1c, e) * lane_load<V>(p + x);
      else
        rx = lane_load<V>(r + x);
      if constexpr (kTerm) rx -= coefficient_at(abar_ij, e) * lane_load<V>(G + x);
      lane_store(r + x, rx);
      if constexpr (kFinal) {
        const V Qx = rx - coefficient_at(abar_ii, e) * lane_load<V>(guess + x);
        norm2 += w[e] * (Qx[0] * Qx[0] + Qx[1] * Qx[1]);
        lane_store(Q0 + x, Qx);
        lane_store(staged + x, V(t.scale * Qx));
      }
    }
    return norm2;
  }
};
template <bool kFromState, bool kTerm, bool kFinal, class C>
double start_pass(Eigen::Index n, const StartTerms& t, C phi0c, C hcphi1c, C abar_ij, C abar_ii) {
  return run_pass<StartPass<kFromState, kTerm, kFinal, C>>(n, t, phi0c, hcphi1c, abar_ij, abar_ii);
}

/// start_pass over the i terms of stage i (term(j): G_j's lanes and abar_ij); returns |Q_0|^2.
template <class C, class Term>
double start_passes(int i, Eigen::Index n, StartTerms t, C phi0c, C hcphi1c, C abar_ii,
                    Term&& term) {
  if (i == 0) return start_pass<true, false, true>(n, t, phi0c, hcphi1c, abar_ii, abar_ii);
  double norm2 = 0;
  for (int j = 0; j < i; ++j) {
    const auto [G, abar_ij] = term(j);
    t.G = G;
    const bool last = j + 1 == i;
    if (j == 0)
      norm2 = last ? start_pass<true, true, true>(n, t, phi0c, hcphi1c, abar_ij, abar_ii)
                   : start_pass<true, true, false>(n, t, phi0c, hcphi1c, abar_ij, abar_ii);
    else
      norm2 = last ? start_pass<false, true, true>(n, t, phi0c, hcphi1c, abar_ij, abar_ii)
                   : start_pass<false, true, false>(n, t, phi0c, hcphi1c, abar_ij, abar_ii);
  }
  return norm2;
}

/// The predictor's polynomial over n eigen coordinates (stage_predictor.hpp, a dynamic size):
/// out = sum_l w_l g_l over `nodes` arrays g_l, each coordinate summed in registers in Eigen's
/// order (w_0 g_0, then + w_l g_l for l = 1, 2, ...: the same bits). kNodes: `nodes` when it is
/// a compile-time constant (the sum unrolled), else 0.
template <int kLanes, int kNodes>
struct PredictPass {
  static EIGEN_ALWAYS_INLINE void run(Eigen::Index n, const double* const* g,
                                      const double* __restrict w, int nodes,
                                      double* __restrict out) {
    using V = typename Lane<kLanes>::Value;
    const int m = kNodes > 0 ? kNodes : nodes;
    for (Eigen::Index e = 0; e < n; ++e) {
      const Eigen::Index x = kLanes * e;
      V v = w[0] * lane_load<V>(g[0] + x);
      for (int l = 1; l < m; ++l) v += w[l] * lane_load<V>(g[l] + x);
      lane_store(out + x, v);
    }
  }
};
/// PredictPass with the sum unrolled for up to 6 nodes (a method of up to 3 stages, kHistory 1).
/// (As Eigen's expressions, one scalar pass per node; with the node loop not unrolled, as costly.
/// callgrind, sine-Gordon N = 32, instructions per grad U: SERKN3s4(1) 6,633 -> 6,470, SERKN2s3
/// 6,597 -> 6,510.)
template <int kLanes>
void predict_pass(Eigen::Index n, const double* const* g, const double* w, int nodes, double* out) {
  switch (nodes) {
    case 1:
      return run_pass<PredictPass<kLanes, 1>>(n, g, w, nodes, out);
    case 2:
      return run_pass<PredictPass<kLanes, 2>>(n, g, w, nodes, out);
    case 3:
      return run_pass<PredictPass<kLanes, 3>>(n, g, w, nodes, out);
    case 4:
      return run_pass<PredictPass<kLanes, 4>>(n, g, w, nodes, out);
    case 5:
      return run_pass<PredictPass<kLanes, 5>>(n, g, w, nodes, out);
    case 6:
      return run_pass<PredictPass<kLanes, 6>>(n, g, w, nodes, out);
    default:
      return run_pass<PredictPass<kLanes, 0>>(n, g, w, nodes, out);
  }
}

}  // namespace erkn::detail
