// Modified kicks (force-gradient methods and correctors, docs/design.md, "Beyond plain kicks"):
// since q^T M q commutes with U, {{A, B}, B} = |grad U|^2 for A = 1/2 p^T p + 1/2 q^T M q, B = U,
// is a function of q alone and its flow is a kick too. Stage i of such a method kicks
//     p -= h (d_i grad U(Q_i) + h^2 e_i G(Q_i)),   G = grad(|grad U|^2) = 2 Hess U grad U
// (methods.spec's `modified` convention, the one the generator certifies), which the explicit
// stepper does as one kick by h with the stage force F_i = d_i g + h^2 e_i G, g = grad U(Q_i).
#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>
#include <span>

#include "erkn/method.hpp"
#include "erkn/system.hpp"
#include "stage_checks.hpp"

namespace erkn::detail {

/// Throws erkn::Error, before anything is built, when `method` has modified kicks and `system`
/// neither hessian_vector_product nor hessian; the message names the methods that need neither.
void require_modified_force(const Method& method, const System& system);

/// The kicks of a method with h folded in: stage i kicks p -= h weight(i) force_i, with force_i
/// = g for a plain kick (weight d_i) and F_i = d_i g + h2e(i) G for a modified one (weight 1).
class KickWeights {
 public:
  KickWeights(const Method& method, double h);
  int stages() const { return s_; }
  double h() const { return h_; }
  double weight(int i) const { return weight_[size_t(i)]; }
  double h2e(int i) const { return h2e_[size_t(i)]; }  ///< h^2 e_i (0: a plain kick)
  /// When the first kick can reuse the last stage's force (c_1 = 0, c_s = 1: the same point),
  /// its weight on that force: d_1 for plain kicks, r for modified ones with (d_1, e_1) =
  /// r (d_s, e_s); none when it cannot (plain and modified, or other mixtures of g and G).
  const std::optional<double>& fsal() const { return fsal_; }

 private:
  int s_;
  double h_;  // (the kicks' h d_i are formed as they are used)
  // (Set for the s_ stages only, the rest never read: zeroing both took two rep stos, ~2 % of a
  // construction at d = 1, perf.)
  std::array<double, kMaxStages> weight_, h2e_;
  std::optional<double> fsal_;
};

/// Adds h2e G(Q) to d_i g in g (g = grad U(Q) on entry), through the System's Hessian-vector
/// product (or else its dense Hessian), or through one compiled into the step, counted in
/// `products`; the result is checked as the gradient is (size, finiteness), the errors naming the
/// callback.
class ModifiedForce {
 public:
  explicit ModifiedForce(Eigen::Index d) : Hv_(Eigen::VectorXd::Zero(d)) {}
  template <int D = Eigen::Dynamic>
  void apply(const System& system, const Eigen::VectorXd& Q, double d_i, double h2e,
             Eigen::VectorXd& g, int i, const StepPlace& at, long& products) {
    const Eigen::Index d = Q.size();
    if (system.hessian_vector_product) {
      system.hessian_vector_product(Q, g, Hv_);
    } else {
      H_.resize(d, d);
      system.hessian(Q, H_);
      Hv_.noalias() = H_ * g;
    }
    ++products;
    if (Hv_.size() != d) gradient_of_wrong_size(Hv_, d, i, at, kCallback);
    add<D>(Hv_, d_i, h2e, g, i, at);
  }
  /// The same through gradient.product(Q, v, hv) (explicit_stepper.hpp, CompiledGradient) on
  /// the stepper's vectors: a fixed-size Hv on the stack, or this one's (sized).
  template <int D, class Gradient, class Vector>
  EIGEN_ALWAYS_INLINE void apply_compiled(const Gradient& gradient, const Vector& Q, double d_i,
                                          double h2e, Vector& g, int i, const StepPlace& at,
                                          long& products) {
    ++products;
    if constexpr (D == Eigen::Dynamic) {
      gradient.product(Q, g, Hv_);
      add<D>(Hv_, d_i, h2e, g, i, at);
    } else {
      Vector Hv;
      gradient.product(Q, g, Hv);
      add<D>(Hv, d_i, h2e, g, i, at);
    }
  }

 private:
  // g = d_i g + 2 h2e Hv (G = 2 Hess U grad U), Hv checked finite first.
  template <int D, class W, class Vector>
  EIGEN_ALWAYS_INLINE static void add(const W& Hv, double d_i, double h2e, Vector& g, int i,
                                      const StepPlace& at) {
    if (!all_finite<D>(Hv.data(), g.size())) non_finite_gradient(i, at, kCallback);
    g = d_i * g + (2 * h2e) * Hv;
  }

  static constexpr const char* kCallback = "hessian_vector_product";
  Eigen::VectorXd Hv_;
  Eigen::MatrixXd H_;  // (only without hessian_vector_product)
};

}  // namespace erkn::detail
