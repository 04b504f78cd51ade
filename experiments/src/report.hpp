// docs/results.md (every table of a run) and docs/summary.md (its verdict), written by the run.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "experiment.hpp"
#include "stiff_scene.hpp"

namespace ex {

struct RunInfo {
  std::string command;  ///< the command line that produced the run
  std::string mode;     ///< "quick", "full", or "custom"
  double wall_seconds = 0;
  double cpu_seconds = 0;  ///< the process's CPU time (the machine may be shared)
  int repeats = 0;
  /// Registry methods run under the name of an identical one: "RKN2s3pf = RKN2s3".
  std::vector<std::string> identical;
  int rounds = 0;  ///< interleaved re-timing rounds of the deciding runs (retime.hpp)
};

/// Writes `file` (results.md) and summary.md beside it (the verdict alone).
/// `stiff`: the stiff scene, one result per kappa (may be empty).
void write_report(const std::filesystem::path& file, const RunInfo& info,
                  const std::vector<ProblemResult>& problems,
                  const std::optional<ScalingResult>& scaling,
                  const std::vector<StiffResult>& stiff);

}  // namespace ex
