// erkn::System: the oscillatory Hamiltonian system
//     H(q, p) = 1/2 p^T p + 1/2 q^T M q + U(q),     q'' + M q = -grad U(q).
#pragma once

#include <Eigen/Core>
#include <functional>

#include "erkn/stiffness.hpp"

namespace erkn {

struct System {
  /// The linear part M (scalar, diagonal, circulant or dense).
  Stiffness M = Stiffness::scalar(0.0);
  /// Required: writes grad U(q) into g (g arrives sized like q; assigning into it allocates
  /// nothing). Must return finite values of the size of q.
  std::function<void(const Eigen::VectorXd& q, Eigen::VectorXd& g)> gradient;
  /// Optional: U(q), for Integrator::energy().
  std::function<double(const Eigen::VectorXd& q)> potential;
  /// Optional: writes the Hessian of U at q into H (arrives sized d x d). Used by the Newton
  /// fallback of the stage solver for d <= 256; without it a finite-difference Jacobian is used.
  /// Beyond d = 256 the fallback is matrix-free (directional differences of the gradient) and
  /// never calls it.
  std::function<void(const Eigen::VectorXd& q, Eigen::MatrixXd& H)> hessian;
  /// Optional: writes Hess U(q) v into Hv (arrives sized like q), as scipy's `hessp`. Methods
  /// with modified kicks (Method::has_modified_kicks) need it, or else `hessian`: their stage i
  /// kicks p -= h d_i grad U(Q_i) + h^3 e_i G(Q_i) with the modified force
  ///     G = grad(|grad U|^2) = 2 Hess U(Q_i) grad U(Q_i),
  /// which the runtime forms as 2 hessian_vector_product(Q_i, grad U(Q_i)) (with only `hessian`
  /// set: 2 H grad U, O(d^2)). Statistics::hessian_vector_products counts the calls; a closed
  /// form usually costs about one gradient (sine-Gordon: cos(q) v; FPU: a sum over springs).
  std::function<void(const Eigen::VectorXd& q, const Eigen::VectorXd& v, Eigen::VectorXd& Hv)>
      hessian_vector_product;
};

}  // namespace erkn
