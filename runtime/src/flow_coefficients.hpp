// The exact flow of q'' + M q = 0 over tau_k = h (c_k - c_{k-1}), k = 0..s (c_{-1} = 0,
// c_s = 1): an explicit method (abar_ii = 0) is this flow alternated with kicks
// p -= h d_k grad U(Q_k) (docs/design.md §1, the explicit family). Per eigenvalue lambda
// (w = sqrt(lambda), x = w tau) the flow is [q; p] <- [cos x, sin(x)/w; -w sin x, cos x] [q; p];
// compensated summation reads cos x - 1 = -2 sin^2(x/2) instead, without cancellation, and never
// cos x (increment form, explicit_passes.hpp), so each flow keeps one of the two (plain passes
// never read cos x - 1): three arrays per flow, not four (at 256^2 a flow's array is 65 fresh
// pages per construction). One sincos of x/2 gives all of them (sin x = 2 sin(x/2) cos(x/2)), and a
// tau_k equal to an earlier one (symmetric methods: every tau but the middle one) shares its
// coefficients. Flow s + 1 is the merged one, over tau_s + tau_0: the last flow of a step and the
// first of the next are one exact flow.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include "erkn/method.hpp"
#include "step_coefficients.hpp"

namespace erkn::detail {

template <class Coef>
class FlowCoefficients {
  // (Allocated with a scalar M too: 3 (kMaxStages + 2) doubles inside would make the explicit
  // stepper at d <= 4 larger than the blocks glibc's per-thread cache serves, 1032 bytes.)
  using Slots = CoefficientSlots<Coef, 3 * (kMaxStages + 2), false>;

 public:
  using Value = typename Slots::Value;

  /// compensated: cosine() is cos(w tau) - 1 (compensated summation's), else cos(w tau).
  FlowCoefficients(const Method& method, double h, const Eigen::VectorXd& lambda, bool compensated)
      : slots_(3 * distinct_taus(method, h), lambda.size()) {
    for (Eigen::Index e = 0; e < lambda.size(); ++e) {
      const double w = std::sqrt(lambda[e]), inv_w = w == 0 ? 0 : 1 / w;
      for (int k = 0, next = 0; k <= method.stages() + 1; ++k) {
        if (slot_[k] != next) continue;  // (shares an earlier flow's coefficients)
        ++next;
        const double t = tau(method, h, k), half = 0.5 * w * t;
        // (One sincos; none at half = +-0, a flow that does not move or w = 0, whose sine and
        // cosine are exactly half and 1: callgrind, ~160 instructions a call.)
        const bool still = half == 0;
        const double s = still ? half : std::sin(half), c = still ? 1.0 : std::cos(half);
        const double cm1 = -2 * s * s, sinc = w == 0 ? t : 2 * s * c * inv_w;
        slots_.set(3 * slot_[k], e, compensated ? cm1 : 1 + cm1);
        slots_.set(3 * slot_[k] + 1, e, sinc);
        slots_.set(3 * slot_[k] + 2, e, -lambda[e] * sinc);
      }
    }
  }

  bool moves(int k) const { return moves_[k]; }  ///< tau_k != 0
  /// The flow over tau_s + tau_0: the last of a step merged with the first of the next.
  static int merged(const Method& method) { return method.stages() + 1; }
  /// cos(w tau_k), or compensated cos(w tau_k) - 1 (1 + it is the plain one, bit for bit).
  Value cosine(int k) const { return slots_.at(3 * slot_[k]); }
  Value sinc(int k) const { return slots_.at(3 * slot_[k] + 1); }   ///< sin(w tau_k) / w
  Value msinc(int k) const { return slots_.at(3 * slot_[k] + 2); }  ///< -w sin(w tau_k)

 private:
  static double tau(const Method& method, double h, int k) {
    const double* c = method.table().c;
    const int s = method.stages();
    if (k == s + 1) return tau(method, h, s) + tau(method, h, 0);
    return h * ((k < s ? c[k] : 1.0) - (k > 0 ? c[k - 1] : 0.0));
  }

  // Two taus within the rounding of the nodes c (each within eps/2 of its exact value, and
  // tau_k h times a difference of two) are the same drift: a symmetric method's c_k - c_(k-1)
  // and its mirror image 1 - c_(s-k) ... differ by that much. Distinct drifts of the registry's
  // methods differ by more than 1e-3 h.
  static constexpr double kSameTau = 4 * std::numeric_limits<double>::epsilon();

  // Sets moves_ and slot_ (flow k's coefficients are those of distinct tau number slot_[k]);
  // returns the number of distinct taus.
  int distinct_taus(const Method& method, double h) {
    std::array<double, kMaxStages + 2> taus;
    int distinct = 0;
    for (int k = 0; k <= method.stages() + 1; ++k) {
      taus[k] = tau(method, h, k);
      moves_[k] = taus[k] != 0;
      slot_[k] = std::int8_t(distinct);
      for (int j = 0; j < k; ++j)
        if (std::abs(taus[j] - taus[k]) <= kSameTau * h) {
          slot_[k] = slot_[j];
          break;
        }
      if (slot_[k] == distinct) ++distinct;
    }
    return distinct;
  }

  std::array<bool, kMaxStages + 2> moves_;
  std::array<std::int8_t, kMaxStages + 2> slot_;
  Slots slots_;
};

}  // namespace erkn::detail
