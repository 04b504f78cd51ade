#pragma once
// S(V, z) in two parts: the V-dependent phi values, once per V, and the z-dependent solve. The
// advisor samples many z at each V (and repeats that for each candidate h of its search), where
// recomputing the sines and cosines was 70 % of the time (perf, d = 63).
#include <array>

#include "erkn/stability.hpp"

namespace erkn::detail {

struct StagePhases {
  const Coefficients* k = nullptr;
  double v = 0;  // the V the phi values are taken at (0 for RKN methods)
  double V = 0;  // M's part: joins z in the "nonlinearity" for RKN methods
  bool rkn = false;
  std::array<double, kMaxStages> x0{}, y0{};  // phi0(c_i^2 v), c_i phi1(c_i^2 v)
  double p0 = 1, p1 = 1;                      // phi0(v), phi1(v)
  // Modified kicks: for U = eps q^2/2, G = 2 eps^2 q, so stage j kicks with the weight
  // d_j + 2 z e_j (z = h^2 eps) where a plain kick has d_j; every coefficient of column j is
  // d_j times its value per unit weight (`unit`, the explicit family with d = 1).
  bool modified = false;
  Coefficients unit;
  std::array<double, kMaxStages> d{}, e{};
};

/// The phi values of S(V, .) for a method whose coefficients `k` are evaluated at V (ERKN) or 0
/// (RKN); `k` must outlive the result.
StagePhases stage_phases(const Method& method, const Coefficients& k, double V);
/// S(V, z) from them: the same arithmetic as stability_matrix(method, k, V, z).
StabilityMatrix stability_matrix(const StagePhases& phases, double z);

}  // namespace erkn::detail
