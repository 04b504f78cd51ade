// The raw results of a run, next to its charts: every measurement behind them as CSV (one table
// per kind of run) and all of it as one JSON document, for re-plotting and analysis elsewhere.
#pragma once

#include <filesystem>
#include <optional>
#include <vector>

#include "experiment.hpp"

namespace ex {

/// Writes dir/sweep.csv (error and cost per method and step count), dir/energy.csv (max energy
/// error per method and t_end), dir/scaling.csv (when scaling ran) and dir/results.json.
void write_raw_results(const std::filesystem::path& dir, const std::vector<ProblemResult>& problems,
                       const std::optional<ScalingResult>& scaling);

}  // namespace ex
