// The comparisons of issue 9, per scene and tolerance of the run: the targets table (best method
// erkn ships and best paper method against the best peer) and where the best paper method's time
// goes (breakdown.hpp), with the part intrinsic to the paper's methods.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "experiment.hpp"
#include "summary.hpp"

namespace ex {

/// A best-paper / best-peer ratio above this is analysed for its intrinsic part.
inline constexpr double kPaperTarget = 3;

/// Every scene and tolerance of the comparisons: P1-P3 at kTolerances, each scaling size at its
/// tolerance. The runs point into `problems` and `scaling`.
std::vector<SceneRuns> target_scenes(const std::vector<ProblemResult>& problems,
                                     const std::optional<ScalingResult>& scaling);

/// The target ratios as a markdown table (also printed at the end of a run).
std::string targets_markdown(const std::vector<SceneRuns>& scenes);

/// The breakdown of the best paper method against the best peer per scene, with the ratios at
/// overhead parity and at kEvalsPerStage evaluations per stage.
/// Followed by paper_methods_markdown.
std::string breakdown_markdown(const std::vector<SceneRuns>& scenes);

/// The same breakdown for every paper method that reaches the tolerance, per scene: its measured
/// ∇U per stage and CPU per ∇U against the best peer's.
std::string paper_methods_markdown(const std::vector<SceneRuns>& scenes);

}  // namespace ex
