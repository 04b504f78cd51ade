// Numbers derived from the measurements: cost to reach a tolerance and the ratio to the best
// peer of the same run.
#pragma once

#include <optional>
#include <vector>

#include "experiment.hpp"

namespace ex {

struct Cost {
  std::optional<double> evals, cpu;  ///< empty: tolerance not bracketed by the measurements
  std::optional<double> steps;       ///< step count to the tolerance, read off the same way
};

Cost cost_to_tolerance(const std::vector<Measurement>& sweep, double tolerance);

/// The cheapest peer cost at `tolerance` (evaluations and CPU time taken separately).
Cost best_peer(const ProblemResult& result, double tolerance);

/// The methods a target compares: every method erkn ships (the registry's), the source paper's
/// methods only, or the peers.
enum class Group { shipped, paper, peer };
bool in_group(Family family, bool from_paper, Group group);

/// The cheapest method of a group in CPU time; empty cpu when none reaches the tolerance.
struct Best {
  std::optional<double> cpu;
  std::string name;
  Cost cost;  ///< of that method at the tolerance
};
Best best_of(const ProblemResult& result, Group group, double tolerance);
/// The same for the scaling scene at size index i.
Best best_of(const ScalingResult& result, Group group, size_t i);

/// Mean fixed-point/Newton iterations per stage solve of a run; empty for explicit methods.
std::optional<double> mean_stage_iterations(const RunStats& stats);

/// CPU time to the scaling tolerance of one line at size index i.
std::optional<double> scaling_cpu(const ScalingResult& result, size_t line, size_t i);

/// Index of the ERKN line cheapest at the largest size (first ERKN line if none reached).
std::optional<size_t> best_erkn_line(const ScalingResult& result);

/// a / b when both are known.
std::optional<double> ratio(const std::optional<double>& a, const std::optional<double>& b);

}  // namespace ex
