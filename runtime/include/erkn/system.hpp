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
};

}  // namespace erkn
