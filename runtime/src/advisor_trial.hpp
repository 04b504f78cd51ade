// The step-size advisor's trial run (erkn/advisor.hpp, "Severity"): the first steps of the run
// itself at h, its energy error and the prediction for the whole run.
#pragma once

#include <Eigen/Core>

#include "erkn/advisor.hpp"

namespace erkn::detail {

/// min(o.trial_steps, o.steps) steps of `method` at h from (q0, p0), blow-up guard off; an
/// erkn::Error of a step ends it as a failure (the run cannot go on at h). `explained`: the
/// linear model found a resonance or an unstable band at h (the limit is then
/// energy_tolerance / explained_margin).
TrialRun trial_run(const Method& method, const System& system, double h, const Eigen::VectorXd& q0,
                   const Eigen::VectorXd& p0, const AdvisorOptions& o, bool explained);

/// The verdict of the trial on the linear findings: unstable and resonance findings move to
/// `notes` unless the trial flags h; pole findings stay.
void judge_by_trial(StepSizeAdvice& advice);

}  // namespace erkn::detail
