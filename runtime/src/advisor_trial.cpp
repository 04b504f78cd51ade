#include "advisor_trial.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "blowup_guard.hpp"
#include "erkn/error.hpp"
#include "erkn/integrator.hpp"

namespace erkn::detail {
namespace {

// E(n / kEarly) against E(n) gives the growth exponent.
constexpr long kEarly = 16;

// The trial's measure at the integrator's state: the relative energy error, or without a
// potential E_2 / E_2(0) - 1.
struct Measure {
  bool energy = false;
  double reference = 0, scale = 0;

  Measure(const Integrator& run, const System& system, const Eigen::VectorXd& q0,
          const Eigen::VectorXd& p0)
      : energy(bool(system.potential)) {
    const double e2 = mode_energies(system.M, q0, p0).sum();
    reference = energy ? run.energy() : e2;
    scale = energy ? e2 + std::abs(system.potential(q0)) : e2;
  }
  double operator()(const Integrator& run, const System& system) const {
    const double now = energy ? run.energy() : mode_energies(system.M, run.q(), run.p()).sum();
    const double e = std::abs(now - reference) / scale;
    return std::isnan(e) ? std::numeric_limits<double>::infinity() : e;
  }
};

// error (steps / n)^alpha, alpha = log(error / early) / log kEarly clamped to [0, 1].
double predicted(const TrialRun& t, long steps) {
  if (t.steps >= steps || t.error == 0) return t.error;
  const double alpha =
      t.early > 0 ? std::clamp(std::log(t.error / t.early) / std::log(double(kEarly)), 0.0, 1.0)
                  : 1.0;
  return t.error * std::pow(double(steps) / double(t.steps), alpha);
}

}  // namespace

TrialRun trial_run(const Method& method, const System& system, double h, const Eigen::VectorXd& q0,
                   const Eigen::VectorXd& p0, const AdvisorOptions& o) {
  TrialRun t;
  const long n = std::min(o.trial_steps, o.steps), early = std::max(1L, n / kEarly);
  Options unguarded;
  unguarded.blowup_guard = false;
  try {
    Integrator run(method, system, h, q0, p0, unguarded);
    const Measure measure(run, system, q0, p0);
    if (!(measure.scale > 0)) return t;  // (a state at rest: nothing to measure against)
    while (t.steps < n && std::isfinite(t.error)) {
      run.step();
      t.error = std::max(t.error, measure(run, system));
      if (++t.steps == early) t.early = t.error;
    }
    if (!std::isfinite(t.error)) t.failure = "the energy is no longer finite";
  } catch (const Error& e) {
    t.failure = e.what();
  }
  t.predicted = t.failure.empty() ? predicted(t, o.steps) : std::numeric_limits<double>::infinity();
  t.horizon = o.steps;
  t.limit = system.potential ? o.energy_tolerance / o.trial_margin : BlowupGuard::kGrowthLimit;
  t.flagged = !t.failure.empty() || t.predicted >= t.limit;
  return t;
}

void judge_by_trial(StepSizeAdvice& advice) {
  if (advice.trial.flagged) return;
  auto information = [](const AdvisorFinding& f) { return f.hazard != Hazard::pole; };
  for (const AdvisorFinding& f : advice.findings)
    if (information(f)) advice.notes.push_back(f);
  std::erase_if(advice.findings, information);
}

}  // namespace erkn::detail
