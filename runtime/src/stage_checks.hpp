// The checks every step makes around the user's gradient and on its result, shared by the
// implicit (stepper.hpp) and explicit (explicit_stepper.hpp) steppers: each failure is an
// erkn::Error naming the step, its time and the stage, and the state stays as it was.
#pragma once

#include <Eigen/Core>
#include <bit>
#include <complex>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "erkn/method.hpp"
#include "erkn/system.hpp"

namespace erkn::detail {

/// Where a step is: its number (1-based) and its time at the start, for messages.
struct StepPlace {
  const Method* method = nullptr;
  long step = 0;
  double t = 0;
  /// "pi" or "pi^-1" while a processed method's processor runs on the state at step `step` (the
  /// stage index i of a message is then the processor's kick).
  const char* processor = nullptr;
};

/// The bits of x - x: 0 exactly when x is finite (else a NaN's). OR-ed over an array they say
/// whether every entry is finite: an integer reduction without early exit, which the compiler
/// vectorises (alone, or within a pass that computes x anyway), with a latency of one cycle per
/// packet (a floating-point sum of x * 0, which it may not reorder, has the adder's; a loop
/// ok &= |x| <= max compiled to scalar compares: 6 % of a plain step at N = 2048).
inline std::uint64_t nonfinite_bits(double x) { return std::bit_cast<std::uint64_t>(x - x); }

/// True when x[0..n) are all finite (N: n when it is a compile-time constant).
template <int N = Eigen::Dynamic>
bool all_finite(const double* x, Eigen::Index n) {
  std::uint64_t bits = 0;
  for (Eigen::Index k = 0; k < (N == Eigen::Dynamic ? n : N); ++k) bits |= nonfinite_bits(x[k]);
  return bits == 0;
}
/// y = x, and all_finite(x, n) in the same pass.
inline bool copy_finite(const double* __restrict x, double* __restrict y, Eigen::Index n) {
  std::uint64_t bits = 0;
  for (Eigen::Index k = 0; k < n; ++k) y[k] = x[k], bits |= nonfinite_bits(x[k]);
  return bits == 0;
}
inline bool all_finite(const std::complex<double>* x, Eigen::Index n) {
  return all_finite(reinterpret_cast<const double*>(x), 2 * n);
}

/// all_finite over fixed-size arrays, two entries at a time where a size is even: the fixed
/// point's iterate, kept on the stack across the gradient call, was stored as one 16-byte value,
/// and an 8-byte load of its upper half is not forwarded from that store (perf, P3: ~15 % of the
/// samples on that load and its branch; the packed check: -3 % CPU per grad U at P3, A/B in one
/// process). The non-finite bits of every array OR-ed, one test. An odd size: entry by entry.
template <class... A>
[[gnu::always_inline]] inline bool all_finite_values(const A&... a) {
  using V = double __attribute__((vector_size(16)));
  using B = std::uint64_t __attribute__((vector_size(16)));
  B bits{};
  std::uint64_t odd = 0;  // (the last entries of odd sizes)
  const auto take = [&](const auto& x) {
    constexpr int n = int(std::decay_t<decltype(x)>::SizeAtCompileTime);
    static_assert(n > 0, "all_finite_values: fixed-size arrays only (else all_finite)");
    for (int k = 0; k + 1 < n; k += 2) {
      V v;
      std::memcpy(&v, x.data() + k, sizeof v);
      bits |= (B)(v - v);
    }
    if constexpr (n % 2 != 0) odd |= nonfinite_bits(x.data()[n - 1]);
  };
  (take(a), ...);
  return (bits[0] | bits[1] | odd) == 0;
}

/// The D entries of a callback's result x (g) as a fixed-size array, read entry by entry into
/// registers: the callback writes x with scalar stores, and one vector load spanning two of them
/// is not forwarded from the store buffer but waits until they retire (the empty asm keeps GCC
/// from merging the loads again). A stand-alone driver, old and new alternated: the implicit
/// stepper at P3 (d = 2) ~93 -> ~71 ns per stage; the explicit one, construct + integrate against
/// the specialist's loop, P3 Strang 1.18 -> 1.02, SABA2 0.99 -> 0.82, SRKN14a 0.84 -> 0.66.
template <int D>
EIGEN_ALWAYS_INLINE Eigen::Array<double, D, 1> callback_entries(const double* x) {
  Eigen::Array<double, D, 1> v;
  for (int k = 0; k < D; ++k) {
    double entry = x[k];
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
    if constexpr (D > 1) asm("" : "+x"(entry));  // (one entry: no load spans two stores)
#endif
    v[k] = entry;
  }
  return v;
}

/// A stage's force (a fixed-size map, D = 1: one double) as a value of its own: the forces of
/// successive stages are adjacent doubles, each written by one 8-byte store, and GCC vectorized
/// the loops over stages (r_i, eq. (d)'s update, the predictor's advance) into 16-byte loads
/// spanning two of them, which are not forwarded from the store buffer (perf, P2 SERKN2s3). The
/// empty asm keeps each load apart. (Larger forces, each stored as a whole, are read so: a.)
template <class A>
EIGEN_ALWAYS_INLINE auto stored_force(const A& a) {
  if constexpr (A::SizeAtCompileTime == 1) {
    typename A::PlainObject v = a;
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
    asm("" : "+x"(v.coeffRef(0)));
#endif
    return v;
  } else {
    return a;
  }
}

// The errors (stage_checks.cpp: out of line, so the checks inline into the step).
[[noreturn]] void non_finite_stage(int i, const StepPlace& at);
// (callback: the System member that returned g.)
[[noreturn]] void gradient_of_wrong_size(Eigen::VectorXd& g, Eigen::Index d, int i,
                                         const StepPlace& at, const char* callback = "gradient");
[[noreturn]] void non_finite_gradient(int i, const StepPlace& at,
                                      const char* callback = "gradient");
/// A step whose q_{n+1} (or else p_{n+1}) is not finite.
[[noreturn]] void non_finite_result(bool q_ok, const StepPlace& at);

/// g = grad U(Q) (0-based stage i) through gradient(Q, g) (System::gradient, or a gradient
/// compiled into the stepper on fixed-size vectors, erkn/compiled_gradient.hpp), counted in
/// evaluations, refusing a non-finite Q before the call (when check_Q; else the caller knows it
/// finite), and a g of a size other than d or (when check_g; else the caller checks it) with a
/// non-finite entry after. D: d when it is a compile-time constant.
template <int D = Eigen::Dynamic, class Gradient, class Q, class G>
EIGEN_ALWAYS_INLINE void checked_gradient(const Gradient& gradient, const Q& q, G& g,
                                          Eigen::Index d, int i, const StepPlace& at,
                                          long& evaluations, bool check_g = true,
                                          bool check_Q = true) {
  if (check_Q && !all_finite<D>(q.data(), d)) non_finite_stage(i, at);
  gradient(q, g);
  ++evaluations;
  if constexpr (G::SizeAtCompileTime == Eigen::Dynamic)  // (a fixed-size g has size d)
    if (g.size() != d) gradient_of_wrong_size(g, d, i, at);
  if (check_g && !all_finite<D>(g.data(), d)) non_finite_gradient(i, at);
}

/// A step whose q_{n+1} or p_{n+1} would not be finite fails before it changes the state
/// (fixed-size values: one packed test of both, all_finite_values; which of them failed is found
/// only for the message. Entry by entry, with a compare and a branch each, it was ~25 of
/// SERKN2s3's ~713 instructions per step at P3, callgrind).
template <class Q, class P>
[[gnu::always_inline]] inline void require_finite_result(const Q& q_new, const P& p_new,
                                                         const StepPlace& at) {
  if (!all_finite_values(q_new, p_new)) non_finite_result(q_new.allFinite(), at);
}

}  // namespace erkn::detail
