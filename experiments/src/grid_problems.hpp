// The large grid scenes (issue 10): wave equations on tensor grids whose M is the shifted
// discrete Laplacian (LinearPart::grid); no Hessian (no d x d matrix anywhere).
#pragma once

#include "problem.hpp"

namespace ex {

/// 2-D sine-Gordon (the problems library's; shared with the benchmarks).
using erkn::problems::sine_gordon_2d;

/// 3-D Klein-Gordon / phi^4 on [0, 1]^3, Dirichlet, n^3 interior points (the problems
/// library's klein_gordon(n, 3); its key is "KG3D").
inline Problem klein_gordon_3d(int n) { return erkn::problems::klein_gordon(n, 3); }

}  // namespace ex
