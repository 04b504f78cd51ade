// The large grid scenes (issue 10): wave equations on tensor grids whose M is the shifted
// discrete Laplacian (LinearPart::grid); no Hessian (no d x d matrix anywhere).
#pragma once

#include "problem.hpp"

namespace ex {

/// 2-D sine-Gordon (the problems library's; shared with the benchmarks).
using erkn::problems::sine_gordon_2d;

/// 3-D Klein-Gordon / phi^4 u_tt = Lap u - u - u^3 on [0, 1]^3, Dirichlet, n^3 interior points:
/// u0 = 2 sin(pi x) sin(pi y) sin(pi z) + exp(-100 |x - (0.3, 0.4, 0.5)|^2), u_t(0) = 0;
/// M = -Lap_h + 1 (mass shift), U = sum u^4 / 4. Error at t = 1.
Problem klein_gordon_3d(int n);

}  // namespace ex
