#include "erkn/advisor.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "advisor_trial.hpp"
#include "erkn/error.hpp"
#include "erkn/integrator.hpp"
#include "format.hpp"
#include "stage_phases.hpp"

namespace erkn {
namespace {

constexpr double kMaxSearchSteps = 1e5;
// lambda + kappa above -kCurvatureTolerance (lambda + max |kappa|) counts as >= 0: the relative
// accuracy of hessian_bounds_at's finite differences (steps 1e-6), so that round-off in a zero
// curvature (FPU's slow springs at rest: -1.7e-15) is not reported as a growing equation.
constexpr double kCurvatureTolerance = 1e-6;

void validate(const Eigen::VectorXd& eigenvalues, double h, HessianBounds k,
              const AdvisorOptions& o) {
  if (!std::isfinite(h) || h <= 0)
    throw Error("advise_step_size: h must be finite and > 0; got " + format(h));
  if (eigenvalues.size() == 0) throw Error("advise_step_size: no eigenvalues of M given");
  for (Eigen::Index i = 0; i < eigenvalues.size(); ++i)
    if (!std::isfinite(eigenvalues[i]) || eigenvalues[i] < 0)
      throw Error("advise_step_size: eigenvalue " + std::to_string(i) +
                  " of M = " + format(eigenvalues[i]) + " is not finite and >= 0");
  if (!std::isfinite(k.lo) || !std::isfinite(k.hi) || k.lo > k.hi)
    throw Error("advise_step_size: the Hessian bounds [" + format(k.lo) + ", " + format(k.hi) +
                "] are not a finite range");
  const bool ok = o.potential_degree >= 1 && o.potential_degree <= 64 && o.pole_margin >= 0 &&
                  o.pole_margin < 1 && o.trace_tolerance >= 0 && o.z_samples >= 2 &&
                  o.z_samples <= 100000 && o.max_change >= 0 && o.max_change < 1 &&
                  o.search_step > 0 && o.search_step <= 1 && std::isfinite(o.trace_tolerance) &&
                  o.min_excitation >= 0 && o.min_excitation <= 1 && o.steps >= 1 &&
                  o.energy_tolerance > 0 && std::isfinite(o.energy_tolerance) &&
                  o.trial_steps >= 0 && o.trial_margin >= 1 && std::isfinite(o.trial_margin) &&
                  o.explained_margin >= 1 && std::isfinite(o.explained_margin) &&
                  o.saturated_margin >= 1 && std::isfinite(o.saturated_margin) &&
                  o.extended_trial_steps >= 0 && o.ambiguity >= 1 && std::isfinite(o.ambiguity);
  if (!ok)
    throw Error(
        "advise_step_size: invalid AdvisorOptions (need 1 <= potential_degree <= 64, 0 <= "
        "pole_margin < 1, finite trace_tolerance >= 0, 2 <= z_samples <= 100000, 0 <= "
        "max_change < 1, 0 < search_step <= 1, 0 <= min_excitation <= 1, steps >= 1, finite "
        "energy_tolerance > 0, trial_steps >= 0, finite trial_margin >= 1, finite "
        "explained_margin >= 1, finite saturated_margin >= 1, extended_trial_steps >= 0, finite "
        "ambiguity >= 1)");
  // The search tries 2 max_change / search_step step sizes: bounded, so the advice ends.
  if (o.max_change / o.search_step > kMaxSearchSteps)
    throw Error("advise_step_size: AdvisorOptions max_change / search_step = " +
                format(o.max_change / o.search_step) + " search steps exceed the limit " +
                format(kMaxSearchSteps) + "; take a larger search_step");
}

// The sampled kappa values: z_samples points spanning [lo, hi], and 0 when inside.
std::vector<double> kappa_samples(HessianBounds k, int n) {
  std::vector<double> kappa;
  if (k.lo < 0 && k.hi > 0) kappa.push_back(0.0);
  for (int j = 0; j < n; ++j) kappa.push_back(k.lo + (k.hi - k.lo) * j / (n - 1));
  return kappa;  // (hi last)
}

// The coupling angle sigma(V): how far one step with Hessian value kappa can turn or stretch the
// stiff mode. At z = 0, S(V, 0) is the rotation by theta = sqrt(V) in the coordinates
// (theta y, h y') (T = diag(theta, 1)); the perturbation E = T (S(V, z) - S(V, 0)) T^-1 moves
// its eigenvalues by its symmetric traceless part (the skew part only shifts theta), whose norm
// is the half-width of the instability tongue in the phase. Maximum over the sampled z.
double coupling_angle(const Method& method, const Coefficients& c, double V,
                      const std::vector<double>& kappa, double h) {
  const double theta = std::sqrt(V);
  const detail::StagePhases phases = detail::stage_phases(method, c, V);
  const StabilityMatrix S0 = detail::stability_matrix(phases, 0.0);
  double sigma = 0;
  for (double k : kappa) {
    const StabilityMatrix S = detail::stability_matrix(phases, h * h * k);
    const double e11 = S.s11 - S0.s11, e22 = S.s22 - S0.s22;
    const double e12 = theta * (S.s12 - S0.s12), e21 = (S.s21 - S0.s21) / theta;
    sigma = std::max(sigma, std::hypot(0.5 * (e11 - e22), 0.5 * (e12 + e21)));
  }
  return sigma;
}

// Numerical resonance (ERKN methods, lambda > 0). Write U as a polynomial of degree D in the
// stiff coordinate y (phase theta = h sqrt(lambda) per step) and the slow ones, whose angular
// frequencies are at most omega_s = sqrt(hi) (the fastest linearised slow oscillation). A
// monomial with r stiff and D - r slow factors carries the phase r theta + m h omega_s per step,
// |m| <= D - r; it is resonant (a small divisor of the modulated Fourier expansion, or a
// parametric tongue of the stiff mode) when that phase is a multiple 2 pi j of 2 pi, j >= 1:
//     |r theta - 2 pi j| <= (D - r) h omega_s + r sigma(V),   r = 1 .. D - 1,
// sigma(V) the tongue's own half-width (coupling_angle). r = 1 is h sqrt(lambda) near 2 pi j
// (the aliased stiff mode forces the slow motion), r = 2 near pi j (parametric resonance), r = 3
// near 2 pi j / 3 (the third harmonic of a cubic force); r = D has no slow factor left to detune.
bool resonance(const Method& method, const Coefficients& c, double h, double lambda,
               const std::vector<double>& kappa, const AdvisorOptions& o, AdvisorFinding& f) {
  const double theta = h * std::sqrt(lambda), two_pi = 2 * std::numbers::pi;
  const double slow = h * std::sqrt(std::max(kappa.back(), 0.0));
  const double sigma = coupling_angle(method, c, lambda * h * h, kappa, h);
  for (int r = 1; r < o.potential_degree; ++r) {
    const double j = std::round(r * theta / two_pi);
    if (j >= 1 && std::abs(r * theta - two_pi * j) <= (o.potential_degree - r) * slow + r * sigma) {
      f.hazard = Hazard::resonance, f.trace = 2 * std::cos(theta), f.pole = two_pi * j / r;
      f.harmonic = r;
      return true;
    }
  }
  return false;
}

// One eigenvalue of M and whether its modes hold energy (a resonance needs it).
struct Mode {
  double lambda = 0;
  bool excited = true;
  auto operator<=>(const Mode&) const = default;
};

// Pole hazard at V (ERKN methods with poles); beyond kPoleSearchMax a method with poles may have
// unknown ones: flagged, pole = inf.
bool pole(const Method& method, double V, const AdvisorOptions& o, AdvisorFinding& f) {
  if (method.kind() != Kind::erkn) return false;
  const bool unknown = !method.entire() && V > generated::kPoleSearchMax;
  const double P =
      unknown ? std::numeric_limits<double>::infinity() : method.pole_within(V, o.pole_margin);
  if (P <= 0) return false;
  f.hazard = Hazard::pole, f.pole = P;
  return true;
}

// The linear test equation over the sampled kappa. Where lambda + kappa >= 0 the solution is
// bounded, and |tr S| > 2 is the method's growth. Where lambda + kappa < 0 the equation grows by
// e^{h mu} per step and so must the method (rho(S) = e^{h mu} + O(h^{p+1})): that growth is
// recorded in `equation`; the method is blamed only when ln rho(S) > kMethodGrowthFactor h mu.
// Returns true for a method finding in f.
bool linear(const Method& method, const Coefficients& c, double h, double lambda,
            const std::vector<double>& kappa, const AdvisorOptions& o, AdvisorFinding& f,
            AdvisorFinding& equation) {
  double worst = 0;
  // (lambda + kappa within the finite-difference Hessian's accuracy of 0 counts as bounded.)
  double largest = 0;
  for (double k : kappa) largest = std::max(largest, std::abs(k));
  const double tolerance = kCurvatureTolerance * (lambda + largest);
  const detail::StagePhases phases = detail::stage_phases(method, c, f.V);
  for (double k : kappa) {
    const StabilityMatrix S = detail::stability_matrix(phases, h * h * k);
    const double tr = S.finite() ? std::abs(S.trace()) : std::numeric_limits<double>::infinity();
    if (lambda + k < -tolerance) {
      const double mu = std::sqrt(-(lambda + k));
      if (mu > equation.rate)
        equation.hazard = Hazard::equation, equation.rate = mu, equation.z = h * h * k,
        equation.trace = S.trace();
      // ln rho(S) for det S = 1: acosh(|tr S| / 2).
      const double excess = (tr > 2 ? std::acosh(tr / 2) : 0) - kMethodGrowthFactor * h * mu;
      if (excess > o.trace_tolerance && excess > worst)
        worst = excess, f.hazard = Hazard::unstable, f.z = h * h * k, f.trace = S.trace();
    } else if (tr - 2 > o.trace_tolerance && tr - 2 > worst) {
      worst = tr - 2, f.hazard = Hazard::unstable, f.z = h * h * k, f.trace = S.trace();
    }
  }
  return worst > 0;
}

// The worst method finding for one eigenvalue at step h, if any; `equation` receives the
// equation's own growth there (rate 0: none).
bool check(const Method& method, double h, Mode mode, const std::vector<double>& kappa,
           const AdvisorOptions& o, AdvisorFinding& f, AdvisorFinding& equation) {
  const bool erkn = method.kind() == Kind::erkn;
  f.lambda = equation.lambda = mode.lambda, f.V = equation.V = h * h * mode.lambda;
  if (pole(method, f.V, o, f)) return true;
  const Coefficients c = method.at(erkn ? f.V : 0.0, 0.0);
  if (linear(method, c, h, mode.lambda, kappa, o, f, equation)) return true;
  return erkn && mode.lambda > 0 && mode.excited &&
         resonance(method, c, h, mode.lambda, kappa, o, f);
}

// True when no mode gives a method finding at h (stops at the first).
bool clean(const Method& method, double h, const std::vector<Mode>& modes,
           const std::vector<double>& kappa, const AdvisorOptions& o) {
  AdvisorFinding f, equation;
  for (Mode mode : modes)
    if (check(method, h, mode, kappa, o, f, equation)) return false;
  return true;
}

// The modes of the eigenvalues: excited unless mode_energy (one per eigenvalue, summed over equal
// eigenvalues) shows less than min_excitation of the total.
std::vector<Mode> modes_of(const Eigen::VectorXd& lambda, const Eigen::VectorXd& energy,
                           double min_excitation) {
  std::vector<Mode> modes(lambda.size());
  for (Eigen::Index i = 0; i < lambda.size(); ++i) modes[i].lambda = lambda[i];
  if (energy.size() == 0) return modes;
  std::vector<Eigen::Index> order(lambda.size());
  for (Eigen::Index i = 0; i < lambda.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return lambda[a] < lambda[b]; });
  const double total = energy.sum();
  for (size_t first = 0, last = 0; first < order.size(); first = last) {
    double sum = 0;
    for (last = first; last < order.size() && lambda[order[last]] == lambda[order[first]]; ++last)
      sum += energy[order[last]];
    for (size_t j = first; j < last; ++j) modes[order[j]].excited = sum >= min_excitation * total;
  }
  return modes;
}

// The nearest h within max_change without a method finding, NaN when none.
double suggestion(const Method& method, double h, std::vector<Mode> modes,
                  const std::vector<double>& kappa, const AdvisorOptions& o) {
  std::sort(modes.begin(), modes.end());  // (distinct modes are enough)
  modes.erase(std::unique(modes.begin(), modes.end()), modes.end());
  for (long j = 1; j * o.search_step <= o.max_change; ++j)
    for (double sign : {-1.0, 1.0}) {
      const double candidate = h * (1 + sign * double(j) * o.search_step);
      if (candidate > 0 && clean(method, candidate, modes, kappa, o)) return candidate;
    }
  return std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

std::string_view to_string(Hazard hazard) {
  switch (hazard) {
    case Hazard::unstable:
      return "unstable";
    case Hazard::resonance:
      return "resonance";
    case Hazard::pole:
      return "pole";
    case Hazard::equation:
      return "the equation grows";
  }
  return "?";
}

StepSizeAdvice advise_step_size(const Method& method, const Eigen::VectorXd& eigenvalues, double h,
                                HessianBounds hessian, const AdvisorOptions& o,
                                const Eigen::VectorXd& mode_energy) {
  validate(eigenvalues, h, hessian, o);
  if (mode_energy.size() != 0 && (mode_energy.size() != eigenvalues.size() ||
                                  !mode_energy.allFinite() || mode_energy.minCoeff() < 0))
    throw Error(
        "advise_step_size: the mode energies must be one finite value >= 0 per "
        "eigenvalue of M (" +
        std::to_string(eigenvalues.size()) + "); got " + std::to_string(mode_energy.size()));
  const std::vector<double> kappa = kappa_samples(hessian, o.z_samples);
  const std::vector<Mode> modes = modes_of(eigenvalues, mode_energy, o.min_excitation);
  StepSizeAdvice advice;
  advice.h = h, advice.hessian = hessian;
  for (Eigen::Index i = 0; i < eigenvalues.size(); ++i) {
    AdvisorFinding f, equation;
    f.index = equation.index = i;
    if (check(method, h, modes[i], kappa, o, f, equation)) advice.findings.push_back(f);
    if (equation.rate > 0) advice.equation.push_back(equation);
  }
  advice.suggested_h = advice.safe() ? h : suggestion(method, h, modes, kappa, o);
  return advice;
}

namespace {

// One line of a report: the finding's eigenvalue, hazard and its evidence.
std::string finding_line(const AdvisorFinding& f, double h) {
  std::ostringstream s;
  s << "  eigenvalue " << f.index << ": lambda = " << format(f.lambda)
    << ", V = h^2 lambda = " << format(f.V) << ": " << to_string(f.hazard);
  if (f.hazard == Hazard::unstable)
    s << " (|tr S(V, z)| = " << format(std::abs(f.trace), 15) << " at z = " << format(f.z)
      << ": the method grows where the equation "
      << (f.lambda + f.z / (h * h) < 0 ? "grows more slowly)" : "is bounded)");
  else if (f.hazard == Hazard::resonance)
    s << " (h sqrt(lambda) = " << format(std::sqrt(f.V)) << " near "
      << format(f.pole / std::numbers::pi, 4) << " pi, harmonic " << f.harmonic
      << "; tr S(V, 0) = " << format(f.trace) << ")";
  else if (std::isinf(f.pole))
    s << " (V beyond " << format(generated::kPoleSearchMax)
      << ", where the method's poles are not known)";
  else
    s << " (pole v = " << format(f.pole) << ")";
  return s.str() + "\n";
}

// The information part: where the differential equation itself grows (at most 3 eigenvalues
// listed).
std::string equation_lines(const std::vector<AdvisorFinding>& equation, double h) {
  if (equation.empty()) return "";
  std::ostringstream s;
  s << "information: the differential equation itself grows along " << equation.size()
    << " eigenvalue(s) of M (lambda + kappa < 0: M + Hessian of U has a negative direction); "
       "every method follows that growth at any h, so it is not a fault of h\n";
  for (size_t i = 0; i < std::min<size_t>(equation.size(), 3); ++i) {
    const AdvisorFinding& f = equation[i];
    s << "  eigenvalue " << f.index << ": lambda = " << format(f.lambda)
      << ", growth rate mu = " << format(f.rate)
      << " per unit time (e^{h mu} = " << format(std::exp(h * f.rate))
      << " per step; the method's |tr S| = " << format(std::abs(f.trace)) << ")\n";
  }
  if (equation.size() > 3) s << "  ...\n";
  return s.str();
}

// The trial run's evidence (none without a trial).
std::string trial_line(const TrialRun& t) {
  if (t.steps == 0 && t.failure.empty()) return "";
  std::ostringstream s;
  s << "  trial run: " << t.steps << " steps at h";
  if (t.steps > t.first_steps)
    s << " (extended: the first " << t.first_steps << " predicted " << format(t.first_predicted, 3)
      << ", near their limit)";
  if (!t.failure.empty()) return s.str() + ", then stopped: " + t.failure + "\n";
  s << ", largest relative energy error " << format(t.error, 3) << " (" << format(t.early, 3)
    << " over its first 1/16), predicted " << format(t.predicted, 3) << " over " << t.horizon
    << " steps against the limit " << format(t.limit, 3)
    << (t.saturated   ? " (saturated: held at its level)"
        : t.explained ? " (a linear hazard explains the growth)"
                      : "")
    << ": " << (t.predicted >= t.limit ? "flagged" : "within it") << "\n";
  if (t.mode_rate > 0)
    s << "  a quiet mode (" << format(t.mode_share, 3)
      << " of the linear energy) grows exponentially, " << format(t.mode_rate, 3)
      << " per step: it takes over " << format(t.takeover, 3) << " steps after the first "
      << t.first_steps
      << (double(t.first_steps) + t.takeover <= double(t.horizon) ? ", within the run: flagged"
                                                                  : ", after the run")
      << "\n";
  return s.str();
}

// The linear findings the trial shows to be harmless (at most 3 listed).
std::string note_lines(const std::vector<AdvisorFinding>& notes, double h) {
  if (notes.empty()) return "";
  std::string s = "information: " + std::to_string(notes.size()) +
                  " eigenvalue(s) of M in an unstable band or at a resonance, which the trial run "
                  "shows to stay within the limit\n";
  for (size_t i = 0; i < std::min<size_t>(notes.size(), 3); ++i) s += finding_line(notes[i], h);
  return s + (notes.size() > 3 ? "  ...\n" : "");
}

}  // namespace

std::string StepSizeAdvice::report(const Method& method) const {
  std::ostringstream s;
  s << method.name() << ", h = " << format(h, 12) << ", Hessian of U in [" << format(hessian.lo)
    << ", " << format(hessian.hi) << "]: ";
  if (safe())
    s << "the method is stable at h: no eigenvalue of M in an unstable band, at a resonance of "
         "an excited mode or near a pole"
      << (trial.steps > 0 ? " that the trial run finds harmful\n" : "\n");
  else
    s << findings.size() << " eigenvalue(s) of M flagged"
      << (trial.flagged ? "; the trial run flags h\n" : "\n");
  for (const AdvisorFinding& f : findings) s << finding_line(f, h);
  s << trial_line(trial) << note_lines(notes, h) << equation_lines(equation, h);
  if (safe()) return s.str();
  if (std::isnan(suggested_h) && findings.empty())
    s << "only the trial run flags h (a breakdown the linear model does not see): take a smaller "
         "h or a more accurate method\n";
  else if (std::isnan(suggested_h))
    s << "no step size within the searched range avoids them\n";
  else
    s << "nearest step size without findings: h = " << format(suggested_h, 12) << "\n";
  return s.str();
}

HessianBounds hessian_bounds_at(const System& system, const Eigen::VectorXd& q) {
  const Eigen::Index d = q.size();
  if (d == 0 || !q.allFinite()) throw Error("hessian_bounds_at: q is empty or not finite");
  if (d > 2000)
    throw Error("hessian_bounds_at: d = " + std::to_string(d) +
                " > 2000; give the Hessian bounds of U instead");
  Eigen::MatrixXd K(d, d);
  if (system.hessian) {
    system.hessian(q, K);
  } else {
    if (!system.gradient) throw Error("hessian_bounds_at: System::gradient is not set");
    Eigen::VectorXd g0(d), g(d), x = q;
    system.gradient(q, g0);
    for (Eigen::Index j = 0; j < d; ++j) {
      const double step = 1e-6 * std::max(1.0, std::abs(q[j]));
      x[j] = q[j] + step;
      system.gradient(x, g);
      x[j] = q[j];
      K.col(j) = (g - g0) / step;
    }
  }
  if (K.rows() != d || K.cols() != d || !K.allFinite())
    throw Error("hessian_bounds_at: the Hessian at q is not a finite " + std::to_string(d) + "x" +
                std::to_string(d) + " matrix");
  const Eigen::MatrixXd sym = 0.5 * (K + K.transpose());
  const Eigen::VectorXd kappa =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(sym, Eigen::EigenvaluesOnly).eigenvalues();
  return {kappa.minCoeff(), kappa.maxCoeff()};
}

HessianBounds hessian_bounds_along(const Method& method, const System& system, double h,
                                   const Eigen::VectorXd& q0, const Eigen::VectorXd& p0,
                                   long steps) {
  if (steps < 0) throw Error("hessian_bounds_along: steps = " + std::to_string(steps) + " < 0");
  Integrator run(method, system, h, q0, p0);
  HessianBounds k = hessian_bounds_at(system, q0);
  for (long n = 0; n < steps; ++n) {
    run.step();
    const HessianBounds at = hessian_bounds_at(system, run.q());
    k.lo = std::min(k.lo, at.lo), k.hi = std::max(k.hi, at.hi);
  }
  return k;
}

StepSizeAdvice advise_step_size(const Method& method, const System& system, double h,
                                const Eigen::VectorXd& q0, const Eigen::VectorXd& p0,
                                const AdvisorOptions& options) {
  const Eigen::VectorXd energy = mode_energies(system.M, q0, p0);  // (checks q0, p0)
  StepSizeAdvice advice = advise_step_size(method, system.M.eigenvalues(), h,
                                           hessian_bounds_at(system, q0), options, energy);
  if (options.trial_steps == 0) return advice;
  const bool explained = std::ranges::any_of(
      advice.findings, [](const AdvisorFinding& f) { return f.hazard != Hazard::pole; });
  advice.trial = detail::trial_run(method, system, h, q0, p0, options, explained);
  detail::judge_by_trial(advice);
  if (advice.safe())
    advice.suggested_h = h;
  else if (advice.findings.empty())
    advice.suggested_h = std::numeric_limits<double>::quiet_NaN();  // (only the trial flags h)
  return advice;
}

}  // namespace erkn
