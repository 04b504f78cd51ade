// Refuses a step size h for which some v = h^2 lambda (lambda an eigenvalue of M) lies within a
// relative pole_tolerance of a pole of the method, naming the pole and the nearest safe h.
#pragma once

#include <Eigen/Core>

#include "erkn/method.hpp"

namespace erkn::detail {

void check_step_size(const Method& method, double h, const Eigen::VectorXd& eigenvalues,
                     double pole_tolerance);

/// The step size nearest to h for which no h^2 lambda is within pole_tolerance of a pole.
double nearest_safe_step(const Method& method, double h, const Eigen::VectorXd& eigenvalues,
                         double pole_tolerance);

}  // namespace erkn::detail
