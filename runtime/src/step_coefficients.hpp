// The coefficients of one step, evaluated once per (h, M) at every eigenvalue of M and scaled by
// the powers of h they appear with. Coef is double (one eigenvalue: scalar M, RKN methods),
// Eigen::Array<double, N, 1> (N eigen coordinates: a diagonal M of a fixed dimension; the values
// inside the object) or Eigen::ArrayXd (an array over the eigen coordinates, all in one
// allocation); the accessors return the value or a read-only map.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <numeric>
#include <type_traits>
#include <vector>

#include "erkn/method.hpp"
#include "phi.hpp"

namespace erkn::detail {

/// The number of Scalars from one array's start to the next: m rounded up to a whole cache line
/// (64 bytes; every array then starts on Eigen's alignment for dynamic arrays, and the maps
/// vectorise as an ArrayXd would), and one line more when that is a multiple of 4 KB. Arrays
/// exactly 4 KB apart share their L1 sets and their 4 KB store-to-load aliasing: a pass over
/// 8-12 of them at once then stalls (the issue measured a compensated Strang loop at N = 8192
/// from 6.6 to 5.5 ms with the extra line). An array shorter than a line takes the power of two
/// of Scalars at or above m (at least Eigen's alignment), so arrays share lines but none spans
/// two: a line each made FlowCoefficients' block with a diagonal M of d <= 4 1152-1728 bytes for
/// 6 explicit methods, beyond the 1032 glibc's per-thread cache serves, and every Integrator so
/// constructed after small frees merged glibc's fastbins first (malloc_consolidate; perf, P3,
/// construct + 20 steps amid a user's small frees: 1.8-2.5 % of the time, allocation_test.cpp).
template <class Scalar>
Eigen::Index aligned_stride(Eigen::Index m) {
  constexpr Eigen::Index line = 64, page = 4096;
  static_assert(line % EIGEN_MAX_ALIGN_BYTES == 0 && line % sizeof(Scalar) == 0);
  constexpr Eigen::Index unit = line / Eigen::Index(sizeof(Scalar));
  if (m < unit) {
    constexpr Eigen::Index aligned =
        std::max<Eigen::Index>(1, EIGEN_MAX_ALIGN_BYTES / sizeof(Scalar));
    return Eigen::Index(std::bit_ceil(std::uint64_t(std::max(m, aligned))));
  }
  Eigen::Index stride = (m + unit - 1) / unit * unit;
  if (stride * Eigen::Index(sizeof(Scalar)) % page == 0) stride += unit;
  return stride;
}

/// The coordinates of a Coef when their number is a compile-time constant: 1 for double, N for
/// Eigen::Array<double, N, 1>; Eigen::Dynamic for Eigen::ArrayXd.
template <class Coef>
constexpr int fixed_coordinates() {
  if constexpr (std::is_same_v<Coef, double>)
    return 1;
  else
    return Coef::SizeAtCompileTime;
}

/// Coefficient slots evaluated at every eigen coordinate: Coef double holds one value per slot
/// (one eigenvalue: scalar M, RKN methods), Eigen::Array<double, N, 1> N values (a diagonal M of
/// a fixed dimension), each slot N apart: at most kMax slots inside the object, no allocation,
/// unless kInside is false: then the slots used, in one allocation. Eigen::ArrayXd holds an array
/// per slot, all in one allocation. at() returns the value or a read-only map.
template <class Coef, int kMax, bool kInside = true>
class CoefficientSlots {
 public:
  static constexpr bool kScalar = std::is_same_v<Coef, double>;
  static constexpr int kFixed = fixed_coordinates<Coef>();  // (coordinates, or Eigen::Dynamic)
  static constexpr bool kArrayInside = kFixed != Eigen::Dynamic && kInside;
  using Value =
      std::conditional_t<kScalar, double,
                         std::conditional_t<kFixed == Eigen::Dynamic,
                                            Eigen::Map<const Eigen::ArrayXd, Eigen::AlignedMax>,
                                            Eigen::Map<const Coef>>>;

  CoefficientSlots(int slots, Eigen::Index m)
      : m_(m), stride_(kFixed != Eigen::Dynamic ? kFixed : aligned_stride<double>(m)) {
    if constexpr (!kArrayInside) values_.resize(slots * stride_);
  }
  void set(int slot, Eigen::Index e, double x) { values_[slot * stride() + e] = x; }
  /// Every slot's value at coordinate from, copied to coordinate to.
  void copy(int slots, Eigen::Index from, Eigen::Index to) {
    for (int slot = 0; slot < slots; ++slot)
      values_[slot * stride() + to] = values_[slot * stride() + from];
  }
  Value at(int slot) const {
    if constexpr (kScalar)
      return values_[slot];
    else if constexpr (kFixed != Eigen::Dynamic)
      return Value(values_.data() + slot * kFixed);
    else
      return Value(values_.data() + slot * stride_, m_);
  }

 private:
  // From one slot to the next: a constant when fixed (at P3, d = 2, loading and multiplying
  // stride_ and the allocation's address were ~6 instructions per coefficient the step reads).
  Eigen::Index stride() const {
    if constexpr (kFixed != Eigen::Dynamic)
      return kFixed;
    else
      return stride_;
  }

  using Values =
      std::conditional_t<kArrayInside, std::array<double, kMax*(kArrayInside ? kFixed : 1)>,
                         Eigen::ArrayXd>;
  Eigen::Index m_, stride_;
  // (Not value-initialised: every slot is set before it is read. Inside, 16-byte aligned: the
  // fixed-size slots of an even D are read through aligned maps, SerialSpace::co. Outside
  // (FlowCoefficients) its natural alignment: the explicit stepper's layout stays as it was.)
  alignas(kArrayInside ? 16 : alignof(Values)) Values values_;
};

/// For each entry of lambda, the index of the first entry with exactly the same value (itself
/// when none comes before it): M's eigenvalues repeat (a circulant M has each twice, a grid's
/// symmetric axes more), and a method's coefficients at v are costly (16 long-double sines and
/// cosines for SERKN3s4(1)), so they are evaluated once per distinct value.
inline std::vector<Eigen::Index> first_equal(const Eigen::VectorXd& lambda) {
  std::vector<Eigen::Index> order(size_t(lambda.size())), first(order.size());
  std::iota(order.begin(), order.end(), Eigen::Index(0));
  // Stable: among equal values the lowest index comes first and represents them.
  std::stable_sort(order.begin(), order.end(),
                   [&](Eigen::Index a, Eigen::Index b) { return lambda[a] < lambda[b]; });
  for (size_t k = 0; k < order.size(); ++k)
    first[size_t(order[k])] =
        k > 0 && lambda[order[k]] == lambda[order[k - 1]] ? first[size_t(order[k - 1])] : order[k];
  return first;
}

template <class Coef>
class StepCoefficients {
  // The flat layout for s stages (layout_s): phi0c, hcphi1c, h2bbar, hb (s slots each), h2abar
  // (the lower triangle, s(s+1)/2 slots), then phi0m1, hphi1, mhMphi1. With an allocation sized
  // by the method's s, not by kMaxStages: on a grid every slot is an array over all unknowns.
  static constexpr int slot_count(int s) { return 4 * s + s * (s + 1) / 2 + 3; }
  static constexpr Eigen::Index kShareFrom = 16;
  using Slots = CoefficientSlots<Coef, slot_count(kMaxStages)>;
  using Value = typename Slots::Value;

 public:
  /// v_k = h^2 lambda_k; lambda must have one entry when Coef is double. The caller has checked
  /// every v against the method's poles (check_step_size), so the table is evaluated directly.
  StepCoefficients(const Method& method, double h, const Eigen::VectorXd& lambda)
      : s_(method.stages()),
        last_(slot_count(layout_s()) - 3),
        h_(h),
        slots_(slot_count(layout_s()), lambda.size()) {
    for (int i = 0; i < s_; ++i) abar_row_[size_t(i)] = 4 * layout_s() + Coefficients::packed(i, 0);
    const generated::Table& table = method.table();
    // (Below kShareFrom entries the sort and its allocations would cost more than they save.)
    const std::vector<Eigen::Index> first =
        lambda.size() >= kShareFrom ? first_equal(lambda) : std::vector<Eigen::Index>{};
    // (Not a Coefficients: its value-initialised arrays were a 1.2 KB rep stos per construction,
    // ~2 % of the time of a construct + 1-step run of SERKN2s3 at P3, perf; evaluate writes
    // every entry of the s stages, Table::coefficients.)
    std::array<double, kMaxStages> b, bbar;
    std::array<double, Coefficients::kMaxPacked> abar;
    for (Eigen::Index e = 0; e < lambda.size(); ++e) {
      if (!first.empty() && first[size_t(e)] != e) {  // (first[e] < e: evaluated already)
        slots_.copy(slot_count(layout_s()), first[size_t(e)], e);
        continue;
      }
      const auto set = [&](int slot, double x) { slots_.set(slot, e, x); };
      const double v = h * h * lambda[e];
      method.evaluate(v, b.data(), bbar.data(), abar.data());
      for (int i = 0; i < s_; ++i) {
        const double c = table.c[i];
        const auto [phi0c, phi1c] = phi01(c * c * v);
        set(i, phi0c);
        set(layout_s() + i, h * c * phi1c);
        set(2 * layout_s() + i, h * h * bbar[i]);
        set(3 * layout_s() + i, h * b[i]);
        for (int j = 0; j <= i; ++j) set(abar_slot(i, j), h * h * abar[Coefficients::packed(i, j)]);
      }
      set(last(0), phi0_minus_1(v));
      const double phi1v = phi1(v);  // (once: the libm call is not merged)
      set(last(1), h * phi1v);
      set(last(2), -h * lambda[e] * phi1v);
    }
  }

  double h() const { return h_; }                                 ///< the step size
  Value phi0c(int i) const { return at(i); }                      ///< phi0(c_i^2 V)
  Value hcphi1c(int i) const { return at(layout_s() + i); }       ///< h c_i phi1(c_i^2 V)
  Value abar(int i, int j) const { return at(abar_slot(i, j)); }  ///< h^2 abar_ij(V)
  Value h2bbar(int i) const { return at(2 * layout_s() + i); }    ///< h^2 bbar_i(V)
  Value hb(int i) const { return at(3 * layout_s() + i); }        ///< h b_i(V)
  Value phi0m1() const { return at(last(0)); }                    ///< phi0(V) - 1
  Value hphi1() const { return at(last(1)); }                     ///< h phi1(V)
  Value mhMphi1() const { return at(last(2)); }                   ///< -h M phi1(V) = -(V/h) phi1(V)

 private:
  // (Slot offsets kept, not recomputed from s at every access: the step reads them per stage.)
  int abar_slot(int i, int j) const {
    if constexpr (Slots::kArrayInside)
      return 4 * kMaxStages + Coefficients::packed(i, j);
    else
      return abar_row_[size_t(i)] + j;
  }
  int last(int k) const {
    if constexpr (Slots::kArrayInside)
      return slot_count(kMaxStages) - 3 + k;
    else
      return last_ + k;
  }
  // The stage count the slots are laid out for: with the values inside the object (a fixed
  // Coef, which has room for kMaxStages) kMaxStages, so that every slot's offset is a constant
  // for a constant i, without s_ or abar_row_ loaded; else s (an allocation per slot's array).
  int layout_s() const {
    if constexpr (Slots::kArrayInside)
      return kMaxStages;
    else
      return s_;
  }
  Value at(int slot) const { return slots_.at(slot); }

  int s_;
  int last_;                                // the first of the last three slots
  std::array<int, kMaxStages> abar_row_{};  // abar_slot(i, 0)
  double h_;
  Slots slots_;
};

}  // namespace erkn::detail
