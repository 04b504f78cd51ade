// Where a method's CPU time goes against a peer's at one tolerance, from the run's own numbers:
// CPU ratio = steps ratio × ∇U-per-step ratio × CPU-per-∇U ratio, and what the ratio would be
// with the overhead removed (CPU per ∇U equal to the peer's) and, further, with the implicit
// stages solved in kEvalsPerStage evaluations each. What is left is the part owed to order and
// error constant (the steps ratio) and to the stage count: intrinsic to the method.
#pragma once

#include <optional>
#include <string>

#include "summary.hpp"

namespace ex {

/// ∇U evaluations per implicit stage assumed for the "intrinsic" ratio (a good predictor and a
/// fixed-point iteration that usually converges in one or two sweeps).
inline constexpr double kEvalsPerStage = 1.3;

struct Breakdown {
  std::string method, peer;
  int method_order = 0, peer_order = 0;
  double cpu = 0;             ///< measured CPU-time ratio
  double steps = 0;           ///< step-count ratio: order and error constant
  double evals_per_step = 0;  ///< ∇U-per-step ratio: stages × stage iterations
  double cpu_per_eval = 0;    ///< CPU-per-∇U ratio: the integrator's own work and setup
  double method_seconds_per_eval = 0, peer_seconds_per_eval = 0;  ///< their CPU time per ∇U
  /// The method's measured ∇U evaluations per implicit stage (empty for explicit methods).
  std::optional<double> evals_per_stage;
  /// steps × evals_per_step: the ratio if CPU per ∇U were the peer's (overhead parity).
  double at_parity = 0;
  /// steps × (kEvalsPerStage × implicit stages) / (the peer's ∇U per step): also at
  /// kEvalsPerStage evaluations per stage. Empty for explicit methods.
  std::optional<double> intrinsic;
};

/// The breakdown of `method` against `peer` in `scene`; empty when either misses the tolerance.
std::optional<Breakdown> breakdown(const SceneRuns& scene, const SceneRuns::Run& method,
                                   const Best& peer);

/// Of the implicit methods of `group`, the one with the smallest intrinsic ratio against `peer`
/// (which may not be the group's fastest in CPU time); empty if none reaches the tolerance.
std::optional<Breakdown> smallest_intrinsic(const SceneRuns& scene, Group group, const Best& peer);

}  // namespace ex
