// Linear stability of the methods (paper §4.1) on the test equation
//     y'' + omega^2 y = -eps y,      V = h^2 omega^2,  z = h^2 eps,
// whose exact solution is bounded iff V + z > 0. One step maps (y_n, h y'_n) to
//     (y_{n+1}, h y'_{n+1}) = S(V, z) (y_n, h y'_n),
//     S = [ phi0(V) - z bbar^T N^-1 phi0(c^2 V)     phi1(V) - z bbar^T N^-1 (c phi1(c^2 V)) ]
//         [ -V phi1(V) - z b^T N^-1 phi0(c^2 V)     phi0(V) - z b^T N^-1 (c phi1(c^2 V))    ]
// with N = I + z Abar(V), all coefficients evaluated at V (erkn::Method::at).
//
// RKN methods (the V -> 0 limits) treat the whole force -(omega^2 + eps) y as the nonlinearity:
// their coefficients are the constants at v = 0 and they never see V separately, so
//     S_RKN(V, z) = S_ERKN-formula(0, V + z)   with the V = 0 coefficients,
// i.e. V enters only through the force. This is what erkn::Integrator computes for them.
//
// Regions. The methods are symplectic, so det S = 1 up to round-off: stability_grid reports
// max |det S - 1| and, since S is huge near poles and singular lines, the relative deviation
// |det S - 1| / (|s11 s22| + |s12 s21|). The paper's stability region {rho(S) < 1} is empty. With
// det S = 1 the eigenvalues are on the unit circle iff |tr S| <= 2. A point is classified, with the
// trace tolerance tau (kTraceTolerance unless given), as
//   periodic  |tr S| < 2 - tau: complex pair on the unit circle (the paper's periodicity region
//             rho = 1, tr^2 < 4 det); the numerical solution is bounded for all n;
//   marginal  | |tr S| - 2 | <= tau: a double eigenvalue +-1, rho = 1 up to sqrt(tau); in general
//             a Jordan block, so the solution grows linearly;
//   unstable  |tr S| > 2 + tau: real eigenvalues, rho(S) > 1, the solution grows like rho^n;
//   singular  S is not finite (N = I + z Abar singular, i.e. 1 + z abar_ii(V) = 0);
//   pole      V lies within Method::at's relative tolerance of a pole of the coefficients
//             (the integrator refuses such a step size).
// The region rho(S) <= 1 is periodic + marginal. A matrix whose relative |det S - 1| exceeds
// kDetTolerance is classified by rho(S) alone (contractive if rho < 1 - tau), so a loss of
// symplecticity can never hide as "periodic".
//
// Processed methods psi = pi o K o pi^-1: one step the integrator shows is P S_K P^-1, P the
// processor pi's matrix on the test equation (its drifts the exact flow over pre_drift h, its
// kicks [1 0; -(y z + 2 v z^2) 1], since grad U = eps y and G = 2 eps^2 y). stability_matrix
// returns that conjugate; its trace and det, and so every class and region, are the kernel's.
#pragma once

#include <string_view>
#include <vector>

#include "erkn/method.hpp"

namespace erkn {

struct StabilityMatrix {
  double s11 = 0, s12 = 0, s21 = 0, s22 = 0;
  double trace() const { return s11 + s22; }
  double det() const { return s11 * s22 - s12 * s21; }
  /// |det S - 1| / (|s11 s22| + |s12 s21|): the loss of symplecticity relative to round-off.
  double det_relative_deviation() const;
  /// Largest modulus of the two eigenvalues.
  double spectral_radius() const;
  bool finite() const;
};

/// S(V, z) for any method (see the header comment; RKN methods: the V = 0 formula at V + z).
/// V >= 0; throws erkn::Error (from Method::at) at or near a pole.
StabilityMatrix stability_matrix(const Method& method, double V, double z);
/// The same with the method's coefficients already evaluated at V (ERKN) or at 0 (RKN);
/// processed methods: conjugated by pi's matrix (see the header comment).
StabilityMatrix stability_matrix(const Method& method, const Coefficients& coefficients, double V,
                                 double z);

enum class StabilityClass { periodic, marginal, unstable, contractive, singular, pole };

/// Tolerance tau on |tr S| - 2 used by classify.
inline constexpr double kTraceTolerance = 1e-12;
/// Largest det_relative_deviation() accepted as symplectic by classify.
inline constexpr double kDetTolerance = 1e-8;

StabilityClass classify(const StabilityMatrix& S, double trace_tolerance = kTraceTolerance);
std::string_view to_string(StabilityClass c);
/// True for the region rho(S) <= 1 (periodic or marginal).
inline bool bounded_region(StabilityClass c) {
  return c == StabilityClass::periodic || c == StabilityClass::marginal;
}

struct StabilityPoint {
  double V = 0, z = 0, trace = 0, det = 0, rho = 0;
  StabilityClass cls = StabilityClass::pole;
};

/// S on the grid V_i = vmax * i / (nv - 1), z_j = zmin + (zmax - zmin) * j / (nz - 1), stored
/// V-major (point(i, j) = points[i * nz + j]).
struct StabilityGrid {
  double vmax = 0, zmin = 0, zmax = 0;
  int nv = 0, nz = 0;
  std::vector<StabilityPoint> points;
  /// max |det S - 1| over the finite points.
  double max_det_deviation = 0;
  /// max |det S - 1| / (|s11 s22| + |s12 s21|) over the finite points: round-off (~1e-14) for a
  /// symplectic method, also where S is huge (near poles and singular lines).
  double max_det_relative_deviation = 0;
  /// max |det S - 1| over the points of the region rho(S) <= 1.
  double max_det_deviation_bounded = 0;
  const StabilityPoint& point(int i, int j) const { return points[size_t(i) * nz + j]; }
};

StabilityGrid stability_grid(const Method& method, double vmax, double zmin, double zmax, int nv,
                             int nz);

}  // namespace erkn
