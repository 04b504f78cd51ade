// erkn::advise_step_size: which step sizes h the stability analysis (erkn/stability.hpp) warns
// against for a given problem, and the nearest h it does not warn against.
//
// Model: near a state, q'' + M q = -grad U(q) linearises to q'' + M q = -K q with K the Hessian
// of U. Taking each eigenvalue lambda of M with a Hessian value kappa from a range [lo, hi] that
// bounds K's eigenvalues gives the test equation of stability.hpp with
//     V = h^2 lambda,   z = h^2 kappa,   kappa in [lo, hi].
// For every eigenvalue lambda the advisor reports
//   pole       V within pole_margin (relative) of a pole of the coefficients (ERKN methods);
//   unstable   |tr S(V, z)| > 2 + trace_tolerance for some sampled z: |rho(S)| > 1, the linear
//              solution grows geometrically;
//   resonance  (ERKN methods, lambda > 0) r h sqrt(lambda) within
//                  (D - r) h sqrt(hi) + r sigma(V)
//              of a multiple 2 pi j (j >= 1) for some r = 1 .. D - 1, D the polynomial degree of
//              U (AdvisorOptions::potential_degree). There tr S(V, 0) = 2 cos(h sqrt(lambda)) is
//              harmless, but a harmonic r of the stiff phase meets the phase sqrt(hi) h per step
//              of the slow motion carried by the remaining D - r factors of U: a small divisor of
//              the numerical solution's modulated Fourier expansion (Hairer & Lubich's numerical
//              resonances; r = 2 is the parametric tongue of the stiff mode at h sqrt(lambda) near
//              k pi, r = 1 the aliased stiff mode forcing the slow motion near 2 k pi). sigma(V)
//              is the tongue's half-width from S itself: the symmetric traceless part of
//              S(V, z) - S(V, 0) in the coordinates where S(V, 0) is a rotation, maximised over z.
//              Derivation and the FPU runs that check it: README, "Resonances".
// What it cannot guarantee: K and M need not commute and K changes along the solution, so this is
// a per-eigenvalue model of the linearisation; a range [lo, hi] estimated at the initial state
// can be exceeded later. An h it accepts is not a proof of bounded energy, and a flagged h is not
// a proof of blow-up (an unexcited mode cannot resonate).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "erkn/method.hpp"
#include "erkn/stability.hpp"
#include "erkn/system.hpp"

namespace erkn {

/// Bounds on the eigenvalues of the Hessian of U (the kappa range above).
struct HessianBounds {
  double lo = 0, hi = 0;
};

struct AdvisorOptions {
  /// D: the degree of U as a polynomial (4 for FPU and phi^4; for other U, the degree of the
  /// Taylor terms that matter). Resonances r h sqrt(lambda) ~ 2 pi j are checked for r < D.
  int potential_degree = 4;
  /// Flags V within this relative distance of a pole (wider than the integrator's refusal).
  double pole_margin = 1e-3;
  /// |tr S| > 2 + trace_tolerance is unstable.
  double trace_tolerance = kTraceTolerance;
  /// Points sampled in [h^2 lo, h^2 hi] (the ends and 0, if inside, are always among them).
  int z_samples = 33;
  /// The suggestion is searched in [h (1 - max_change), h (1 + max_change)], relative steps of
  /// search_step, nearest first (the smaller of two equally near); at most 1e5 steps
  /// (max_change / search_step <= 1e5, else erkn::Error).
  double max_change = 0.5;
  double search_step = 1e-3;
};

enum class Hazard { unstable, resonance, pole };
std::string_view to_string(Hazard hazard);

struct AdvisorFinding {
  Eigen::Index index = 0;  ///< of the eigenvalue (Stiffness::eigenvalues() order)
  double lambda = 0, V = 0;
  Hazard hazard = Hazard::unstable;
  double z = 0;      ///< unstable: the sampled z with the largest |tr S|
  double trace = 0;  ///< unstable: tr S(V, z) there; resonance: tr S(V, 0)
  double pole = 0;   ///< pole: the pole; resonance: the resonant phase 2 pi j / r
  int harmonic = 0;  ///< resonance: r
};

struct StepSizeAdvice {
  double h = 0;
  HessianBounds hessian;
  std::vector<AdvisorFinding> findings;  ///< empty: no warning for h
  /// The nearest h without findings, or NaN when none lies within max_change of h.
  double suggested_h = 0;
  bool safe() const { return findings.empty(); }
  /// A human-readable account: every finding, then the suggestion.
  std::string report(const Method& method) const;
};

/// The advice for h given M's eigenvalues and the Hessian bounds; erkn::Error on invalid input
/// (h not finite and > 0, non-finite or negative eigenvalues, lo > hi, invalid options).
StepSizeAdvice advise_step_size(const Method& method, const Eigen::VectorXd& eigenvalues, double h,
                                HessianBounds hessian, const AdvisorOptions& options = {});

/// The Hessian bounds at q: the extreme eigenvalues of System::hessian at q, or of a
/// finite-difference Hessian of System::gradient without it (d gradient evaluations; d <= 2000).
HessianBounds hessian_bounds_at(const System& system, const Eigen::VectorXd& q);

/// The Hessian bounds along a pilot run: the extreme eigenvalues of the Hessian (as in
/// hessian_bounds_at) at q0 and after each of `steps` steps of `method` with step size h from
/// (q0, p0). The range at q0 alone can be far too narrow (FPU: hi = 12.5 at q0, 22.4 by t = 100).
HessianBounds hessian_bounds_along(const Method& method, const System& system, double h,
                                   const Eigen::VectorXd& q0, const Eigen::VectorXd& p0,
                                   long steps);

/// advise_step_size with M's eigenvalues and the Hessian bounds at q0.
StepSizeAdvice advise_step_size(const Method& method, const System& system, double h,
                                const Eigen::VectorXd& q0, const AdvisorOptions& options = {});

}  // namespace erkn
