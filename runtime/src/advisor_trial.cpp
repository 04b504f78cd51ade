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

// A quiet mode holds below kQuietShare of E_2 at the trial's end; its growth counts as steady
// (exponential, not the slowing growth of round-off noise or of energy trickling in through the
// nonlinearity: a power law n^k has early/late rates 2) when the rate over the trial's second
// quarter is at most kSteadyRatio times that over its second half, and large enough: at least
// kMinGrowth-fold over the second half (round-off in a quiet mode wanders by less). kMinGrowth was
// chosen on the training sweep (docs/advisor.md); the others are the definitions above.
constexpr double kQuietShare = 1e-3, kTakeoverShare = 1e-2, kSteadyRatio = 1.5, kMinGrowth = 400;

// The mode energies at n / 4, n / 2 and n steps.
struct ModeCheckpoints {
  Eigen::VectorXd quarter, half, end;
};

// The quiet mode that reaches kTakeoverShare soonest at its steady rate: sets t.mode_rate,
// t.mode_share, t.takeover (steps after the trial; 0 with mode_rate 0: none).
void quiet_growth(const ModeCheckpoints& e, long n, TrialRun& t) {
  const double total = e.end.sum();
  if (!(total > 0) || n < 4) return;
  double soonest = std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < e.end.size(); ++i) {
    const double share = e.end[i] / total;
    if (!(share < kQuietShare) || !(e.quarter[i] > 0) || !(e.half[i] > 0) || !(e.end[i] > 0))
      continue;
    const double early = std::log(e.half[i] / e.quarter[i]) / double(n / 2 - n / 4);
    const double late = std::log(e.end[i] / e.half[i]) / double(n - n / 2);
    const bool steady = early > 0 && early <= kSteadyRatio * late;
    if (!steady || !(late * double(n - n / 2) >= std::log(kMinGrowth))) continue;
    const double takeover = std::log(kTakeoverShare / share) / late;
    if (takeover < soonest) soonest = takeover, t.mode_rate = late, t.mode_share = share;
  }
  if (t.mode_rate > 0) t.takeover = soonest;
}

// An error that grew less than kSaturatedGrowth-fold over the trial's last 15/16 is saturated
// (chosen on the training sweep, docs/advisor.md).
constexpr double kSaturatedGrowth = 1.5;

// error (steps / n)^alpha, alpha = log(error / early) / log kEarly clamped to [0, 1]; the error
// itself when saturated.
double predicted(const TrialRun& t, long steps) {
  if (t.steps >= steps || t.error == 0 || t.saturated) return t.error;
  const double alpha =
      t.early > 0 ? std::clamp(std::log(t.error / t.early) / std::log(double(kEarly)), 0.0, 1.0)
                  : 1.0;
  return t.error * std::pow(double(steps) / double(t.steps), alpha);
}

// The errors over the first n / kEarly steps of the first trial and of the extended one.
struct EarlyErrors {
  long at[2] = {0, 0};
  double error[2] = {0, 0};
};

// The trial on to n steps (from t.steps): the largest error, the early errors, and the mode
// energies at n / 4, n / 2 and n (the state being finite; the first trial's, see TrialRun).
void take_steps(Integrator& run, const System& system, const Measure& measure, long n, TrialRun& t,
                EarlyErrors& early, ModeCheckpoints& modes) {
  const bool first = t.steps == 0;
  while (t.steps < n && std::isfinite(t.error)) {
    run.step();
    t.error = std::max(t.error, measure(run, system));
    ++t.steps;
    for (int k : {0, 1})
      if (t.steps == early.at[k]) early.error[k] = t.error;
    const bool checkpoint = t.steps == n / 4 || t.steps == n / 2 || t.steps == n;
    if (first && checkpoint && run.q().allFinite() && run.p().allFinite())
      (t.steps == n       ? modes.end
       : t.steps == n / 2 ? modes.half
                          : modes.quarter) = mode_energies(system.M, run.q(), run.p());
  }
  if (!std::isfinite(t.error)) t.failure = "the energy is no longer finite";
}

// The prediction, the limit it is held against and the verdict (see erkn/advisor.hpp), with
// `early` the error over the trial's first steps / kEarly.
void judge(TrialRun& t, double early, const System& system, const AdvisorOptions& o) {
  t.early = early;
  t.saturated = t.failure.empty() && t.error > 0 && t.error <= kSaturatedGrowth * t.early;
  t.predicted = t.failure.empty() ? predicted(t, o.steps) : std::numeric_limits<double>::infinity();
  t.horizon = o.steps;
  t.limit = !system.potential ? BlowupGuard::kGrowthLimit
            : t.saturated     ? o.energy_tolerance / o.saturated_margin
            : t.explained     ? o.energy_tolerance / o.explained_margin
                              : o.energy_tolerance / o.trial_margin;
  const bool takeover = t.mode_rate > 0 && double(t.first_steps) + t.takeover <= double(o.steps);
  t.flagged = !t.failure.empty() || t.predicted >= t.limit || takeover;
}

// The first trial of n steps, then (when it is ambiguous) the extended one of `longer` steps.
void trials(Integrator& run, const System& system, const Measure& measure, long n, long longer,
            const AdvisorOptions& o, TrialRun& t) {
  EarlyErrors early{{std::max(1L, n / kEarly), std::max(1L, longer / kEarly)}};
  ModeCheckpoints modes;
  take_steps(run, system, measure, n, t, early, modes);
  t.first_steps = t.steps;
  if (t.failure.empty() && modes.quarter.size() > 0 && modes.half.size() > 0 &&
      modes.end.size() > 0)
    quiet_growth(modes, n, t);
  judge(t, early.error[0], system, o);
  t.first_predicted = t.predicted;
  if (t.flagged || longer <= n || t.predicted < t.limit / o.ambiguity) return;
  take_steps(run, system, measure, longer, t, early, modes);
  judge(t, early.error[1], system, o);
}

}  // namespace

TrialRun trial_run(const Method& method, const System& system, double h, const Eigen::VectorXd& q0,
                   const Eigen::VectorXd& p0, const AdvisorOptions& o, bool explained) {
  TrialRun t;
  t.explained = explained;
  const long n = std::min(o.trial_steps, o.steps);
  const long longer = std::clamp(o.extended_trial_steps, n, o.steps);
  Options unguarded;
  unguarded.blowup_guard = false;
  try {
    Integrator run(method, system, h, q0, p0, unguarded);
    const Measure measure(run, system, q0, p0);
    if (!(measure.scale > 0)) return t;  // (a state at rest: nothing to measure against)
    trials(run, system, measure, n, longer, o, t);
  } catch (const Error& e) {
    t.failure = e.what();
    const bool first = t.first_steps == 0;  // (the first trial failed)
    if (first) t.first_steps = t.steps;
    judge(t, t.early, system, o);
    if (first) t.first_predicted = t.predicted;
  }
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
