// The stiff nonlinear scene: sine-Gordon (N = 32) with U = -kappa sum cos u for growing kappa, so
// the stiffness sits in the nonlinear part, where an exact linear flow does not help and implicit
// stages should pay. Every method runs a step-size sweep per kappa; the coarsest steps at which a
// method fails (unstable, or a stage solver that does not converge) are kept and charted.
#pragma once

#include <vector>

#include "experiment.hpp"

namespace ex {

struct StiffConfig {
  std::vector<double> kappas{1e2, 1e3, 1e4};
  double t_end = 1;
  /// The report's costs are read at these errors; a sweep stops refining a decade below the
  /// smallest.
  std::vector<double> tolerances{1e-3, 1e-6};
};

/// The scene's problem for one kappa: u(0) = sin(2 pi i / N) (amplitude 1: sin u is far from
/// linear), u'(0) = 0, t in [0, 1].
Problem stiff_sine_gordon(double kappa, double t_end);

struct StiffResult {
  double kappa;
  std::vector<double> tolerances;  ///< StiffConfig::tolerances
  ProblemResult result;            ///< sweeps only, no energy runs
};

std::vector<StiffResult> run_stiff(const SolverList& solvers, const StiffConfig& stiff,
                                   const RunConfig& config, Progress& progress);

}  // namespace ex
