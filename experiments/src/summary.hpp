// Numbers derived from the measurements: cost to reach a tolerance and the ratio to the best
// peer of the same run.
#pragma once

#include <optional>
#include <vector>

#include "experiment.hpp"

namespace ex {

struct Cost {
  std::optional<double> evals, cpu;  ///< empty: tolerance not bracketed by the measurements
};

Cost cost_to_tolerance(const std::vector<Measurement>& sweep, double tolerance);

/// The cheapest peer cost at `tolerance` (evaluations and CPU time taken separately).
Cost best_peer(const ProblemResult& result, double tolerance);

/// Mean fixed-point/Newton iterations per stage solve of a run; empty for explicit methods.
std::optional<double> mean_stage_iterations(const RunStats& stats);

/// CPU time to the scaling tolerance of one line at size index i.
std::optional<double> scaling_cpu(const ScalingResult& result, size_t line, size_t i);

/// Index of the ERKN line cheapest at the largest size (first ERKN line if none reached).
std::optional<size_t> best_erkn_line(const ScalingResult& result);

/// a / b when both are known.
std::optional<double> ratio(const std::optional<double>& a, const std::optional<double>& b);

}  // namespace ex
