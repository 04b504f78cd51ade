// erkn::advise_step_size: which step sizes h the stability analysis (erkn/stability.hpp) warns
// against for a given problem, and the nearest h it does not warn against.
//
// Model: near a state, q'' + M q = -grad U(q) linearises to q'' + M q = -K q with K the Hessian
// of U. Taking each eigenvalue lambda of M with a Hessian value kappa from a range [lo, hi] that
// bounds K's eigenvalues gives the test equation of stability.hpp with
//     V = h^2 lambda,   z = h^2 kappa,   kappa in [lo, hi].
// Two kinds of growth are told apart. Where lambda + kappa < 0 the differential equation itself
// grows (y'' = mu^2 y, mu = sqrt(-(lambda + kappa)): a negative direction of M + K, e.g.
// sine-Gordon at u = pi): every method must follow it, and the advisor reports it as
// information (StepSizeAdvice::equation), not as a fault of h. The method's hazards at h, which
// it flags (StepSizeAdvice::findings), are for every eigenvalue lambda:
//   pole       V within pole_margin (relative) of a pole of the coefficients (ERKN methods);
//   unstable   for a sampled z with lambda + kappa >= 0: |tr S(V, z)| > 2 + trace_tolerance,
//              |rho(S)| > 1 where the solution is bounded; with lambda + kappa < 0: the method's
//              growth ln rho(S) per step exceeds kMethodGrowthFactor times the equation's h mu;
//   resonance  (ERKN methods, lambda > 0, the mode excited: see min_excitation) r h sqrt(lambda)
//              within
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
//              A resonance moves energy into or out of the mode at lambda: a mode without energy
//              (the short waves of smooth data on a grid, whose dense spectrum always has some
//              eigenvalue in a band) is not flagged when the state is known.
//              Derivation and the FPU runs that check it: README, "Resonances".
// What it cannot guarantee: K and M need not commute and K changes along the solution, so this is
// a per-eigenvalue model of the linearisation; a range [lo, hi] estimated at the initial state
// can be exceeded later, and energy can reach a mode later.
//
// Severity (advise_step_size with the System, q0 and p0): a linear finding says where growth can
// come from, not that the run grows beyond its criterion (most resonances only raise a bounded
// energy error; a thin tongue at a sampled kappa is detuned by the Hessian changing along the
// solution), and the linear model misses nonlinear breakdown (sine-Gordon at h omega > pi: sin q
// driven at speeds |p| h of order 1 per step). So the verdict comes from a trial run: the first
// min(trial_steps, steps) steps of the run itself (blow-up guard off). Its relative energy error
// E(n) after n steps and E(n / 16) give the growth exponent alpha = log(E(n) / E(n / 16)) / log 16
// in [0, 1] (0: a bounded error, 1/2: a random walk, 1: a drift) and the prediction
//     E(steps) = E(n) (steps / n)^alpha.
// An error that grew less than 1.5-fold over the trial's last 15/16 (alpha <= log 1.5 / log 16)
// is saturated: the prediction is E(n) itself (a resonance's or a plateau's level, which the
// power law would inflate). h is flagged when the trial fails (a stage solver or a non-finite
// state), when the prediction reaches
//   energy_tolerance / saturated_margin  for a saturated error,
//   energy_tolerance / explained_margin  for a growing one that the linear model explains (a
//                                        resonance or an unstable band at h: it saturates later),
//   energy_tolerance / trial_margin      for a growing one nothing linear explains (a nonlinear,
//                                        chaotic exchange between modes, which jumps: a margin),
// or when a quiet mode grows steadily and exponentially and would take over within the run (an
// instability seeded by round-off, invisible in the energy error until then: the symmetric modes
// of a wave grid). An ambiguous first trial (not flagged, its prediction within a factor
// `ambiguity` of its limit) goes on to extended_trial_steps, and the longer trial's prediction,
// made the same way, decides. Pole findings always flag; the other linear findings are kept as
// `notes` (information) unless the trial flags h (then they are its likely cause). Cost: the
// trial's steps plus one U per step and three mode-energy transforms: 8192 steps (8 % of a
// 1e5-step run), 32768 (33 %) where the first 8192 are ambiguous; 8.3 % on average over the
// sweeps of docs/advisor.md (a failed trial stops early).
// An h it accepts is not a proof of bounded energy, and a flagged h is not a proof of blow-up.
// Its false-alarm and miss rates on a sweep of step sizes against 1e5-step runs: docs/advisor.md.
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
  /// A resonance is flagged only at eigenvalues holding at least this share of the state's
  /// E_2 = 1/2 |p|^2 + 1/2 q^T M q (all eigenvalues equal to lambda together), when the state is
  /// known (mode energies given): round-off and smooth data leave short waves far below it.
  double min_excitation = 1e-8;
  /// The run the verdict is about (with the System): its length in steps, and the relative
  /// energy error |H - H_0| / (E_2(q0, p0) + |U(q0)|) it must stay below ("runs clean").
  long steps = 100000;
  double energy_tolerance = 0.5;
  /// Steps of the trial run (with the System; at most `steps`); 0: no trial, and every linear
  /// finding flags h (as advise_step_size without the System does).
  long trial_steps = 8192;
  /// Where the trial's error still grows and the linear model finds no hazard at h, the trial
  /// flags h when its predicted error reaches energy_tolerance / trial_margin: an error growth
  /// nothing linear explains is the nonlinearity's (a chaotic exchange between modes, which
  /// jumps: docs/advisor.md lists the sine-Gordon runs that blow up long after a calm trial), and
  /// a power law extrapolates it poorly.
  double trial_margin = 16;
  /// Where it finds a resonance or an unstable band, against energy_tolerance / explained_margin:
  /// the growth is that hazard's, which saturates at a level the trial may not reach.
  double explained_margin = 5.0 / 3;
  /// Where the error has saturated (grown less than 1.5-fold over the trial's last 15/16),
  /// against energy_tolerance / saturated_margin: the level is known, only its drift is not.
  double saturated_margin = 1.125;
  /// A first trial that does not flag h but predicts at least limit / ambiguity goes on to
  /// extended_trial_steps steps (at most `steps`; <= trial_steps: never), which decide. (The
  /// margins, trial lengths, ambiguity and the quiet-mode check were chosen on a training sweep:
  /// docs/advisor.md.)
  long extended_trial_steps = 32768;
  double ambiguity = 4;
};

/// The trial run's evidence (advise_step_size with the System; see the top of this header).
/// Without System::potential it measures E_2 = 1/2 |p|^2 + 1/2 q^T M q against its start
/// (error = the largest E_2 / E_2(0) - 1) and flags growth beyond the blow-up guard's 1e4.
struct TrialRun {
  long steps = 0;              ///< steps taken (0: no trial)
  long first_steps = 0;        ///< of them, the first trial's (== steps unless it was extended)
  double first_predicted = 0;  ///< the first trial's prediction (what made it ambiguous)
  double error = 0;            ///< the largest relative energy error over the trial
  double early = 0;            ///< the same over its first steps / 16
  double predicted = 0;        ///< error extrapolated to AdvisorOptions::steps
  long horizon = 0;            ///< AdvisorOptions::steps: the run predicted
  double limit = 0;            ///< what predicted is held against
  bool explained = false;      ///< the linear model found a resonance or an unstable band at h
  bool saturated = false;      ///< error < 1.5 early: predicted = error, limit by saturated_margin
  std::string failure;         ///< the erkn::Error that stopped the trial, or why it stopped
  /// A quiet mode (below 1e-3 of E_2 at the first trial's end) whose energy grows steadily and
  /// exponentially, at least 400-fold over the first trial's second half (an instability seeded
  /// by round-off, which the energy error shows only when the mode takes over): its growth rate
  /// per step (0: none), its share of E_2 at the first trial's end, and the steps after it until
  /// the mode holds 1e-2 of E_2 at that rate (it flags h when that happens within the run).
  double mode_rate = 0;
  double mode_share = 0;
  double takeover = 0;
  bool flagged =
      false;  ///< failure, predicted at or beyond the limit, or a takeover within the run
};

/// The method's hazards (unstable, resonance, pole), and `equation`: the differential
/// equation's own growth (lambda + kappa < 0), information only.
enum class Hazard { unstable, resonance, pole, equation };
std::string_view to_string(Hazard hazard);

struct AdvisorFinding {
  Eigen::Index index = 0;  ///< of the eigenvalue (Stiffness::eigenvalues() order)
  double lambda = 0, V = 0;
  Hazard hazard = Hazard::unstable;
  double z = 0;      ///< unstable, equation: the sampled z with the largest growth
  double trace = 0;  ///< unstable, equation: tr S(V, z) there; resonance: tr S(V, 0)
  double rate = 0;   ///< equation: mu = sqrt(-(lambda + kappa)), the growth per unit time
  double pole = 0;   ///< pole: the pole; resonance: the resonant phase 2 pi j / r
  int harmonic = 0;  ///< resonance: r
};

struct StepSizeAdvice {
  double h = 0;
  HessianBounds hessian;
  std::vector<AdvisorFinding> findings;  ///< the method's hazards at h; empty: no warning
  /// Information: eigenvalues where the differential equation itself grows (lambda + kappa < 0
  /// for some kappa); the method follows that growth at any h, so it is no finding.
  std::vector<AdvisorFinding> equation;
  /// Information: the linear model's unstable and resonance findings that the trial run shows to
  /// stay within the criterion (with the System only).
  std::vector<AdvisorFinding> notes;
  /// The trial run (with the System and AdvisorOptions::trial_steps > 0).
  TrialRun trial;
  /// The nearest h without findings (of the linear model), or NaN when none lies within
  /// max_change of h or only the trial flags h (a nonlinear breakdown: take a smaller h).
  double suggested_h = 0;
  bool safe() const { return findings.empty() && !trial.flagged; }
  /// A human-readable account: every finding, then the suggestion.
  std::string report(const Method& method) const;
};

/// The advice for h given M's eigenvalues and the Hessian bounds; erkn::Error on invalid input
/// (h not finite and > 0, non-finite or negative eigenvalues, lo > hi, invalid options, mode
/// energies not one finite value >= 0 per eigenvalue). `mode_energy` (optional): the state's
/// E_2 at each eigenvalue (see min_excitation); empty: every mode counts as excited.
StepSizeAdvice advise_step_size(const Method& method, const Eigen::VectorXd& eigenvalues, double h,
                                HessianBounds hessian, const AdvisorOptions& options = {},
                                const Eigen::VectorXd& mode_energy = {});

/// The Hessian bounds at q: the extreme eigenvalues of System::hessian at q, or of a
/// finite-difference Hessian of System::gradient without it (d gradient evaluations; d <= 2000).
HessianBounds hessian_bounds_at(const System& system, const Eigen::VectorXd& q);

/// The Hessian bounds along a pilot run: the extreme eigenvalues of the Hessian (as in
/// hessian_bounds_at) at q0 and after each of `steps` steps of `method` with step size h from
/// (q0, p0). The range at q0 alone can be far too narrow (FPU: hi = 12.5 at q0, 22.4 by t = 100).
HessianBounds hessian_bounds_along(const Method& method, const System& system, double h,
                                   const Eigen::VectorXd& q0, const Eigen::VectorXd& p0,
                                   long steps);

/// advise_step_size with M's eigenvalues, the Hessian bounds at q0 and the mode energies of
/// (q0, p0), judged by a trial run of the problem (see the top of this header).
StepSizeAdvice advise_step_size(const Method& method, const System& system, double h,
                                const Eigen::VectorXd& q0, const Eigen::VectorXd& p0,
                                const AdvisorOptions& options = {});

/// How much of the state's linear energy sits at each eigenvalue of M (the excitation a resonance
/// needs): e[i] = the part of E_2 = 1/2 |p|^2 + 1/2 q^T M q in the eigen coordinates whose
/// eigenvalue is Stiffness::eigenvalues()[i] (circulant: the cosine and the sine of wave number
/// i), so sum e = E_2 up to round-off; scalar M: one entry, E_2. erkn::Error unless q and p are
/// finite and of one size d > 0 (= M's).
Eigen::VectorXd mode_energies(const Stiffness& M, const Eigen::VectorXd& q,
                              const Eigen::VectorXd& p);

/// The share of the equation's growth a method may add before it counts as the method's: an
/// unstable finding where lambda + kappa < 0 needs ln rho(S) > kMethodGrowthFactor h mu.
inline constexpr double kMethodGrowthFactor = 2;

}  // namespace erkn
