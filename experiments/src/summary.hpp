// Numbers derived from the measurements: cost to reach a tolerance, the best method of a group,
// and the ratio to the best peer of the same run.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "experiment.hpp"

namespace ex {

struct Cost {
  std::optional<double> evals, cpu;  ///< empty: tolerance not bracketed by the measurements
  std::optional<double> steps;       ///< step count to the tolerance, read off the same way
};

/// `round`: with the CPU times of that interleaved timing round (Measurement::round_cpu) where a
/// run has one, else with its best time.
Cost cost_to_tolerance(const std::vector<Measurement>& sweep, double tolerance,
                       std::optional<int> round = std::nullopt);

/// The cheapest peer cost at `tolerance` (evaluations and CPU time taken separately).
Cost best_peer(const ProblemResult& result, double tolerance);

/// The methods a comparison takes: every method erkn ships (the registry's), the source paper's
/// methods only, the registry's explicit methods, its other (implicit) methods, the peers, the
/// peers that integrate q'' + Mq = 0 exactly (exact-flow), or the other peers.
enum class Group { shipped, paper, shipped_explicit, shipped_other, peer, exact_peer, other_peer };
bool in_group(const SolverTraits& traits, Group group);
/// "the best method erkn ships", "the best paper method", ... for sentences.
std::string group_phrase(Group group);

/// One scene at one tolerance: every solver's measurements there.
struct SceneRuns {
  std::string scene;  ///< "P1", "P1 scaling, N = 512", ...
  double tolerance;
  struct Run {
    const SolverTraits* traits;
    const std::vector<Measurement>* measurements;
  };
  std::vector<Run> runs;
};
SceneRuns scene_runs(const ProblemResult& result, double tolerance);
SceneRuns scene_runs(const ScalingResult& result, size_t size_index, double tolerance);

/// The cheapest method of a group in CPU time; empty cpu when none reaches the tolerance.
struct Best {
  std::optional<double> cpu;
  std::string name;
  Cost cost;             ///< of that method at the tolerance
  SceneRuns::Run run{};  ///< that method's traits and runs (null when cpu is empty)
};
/// `round`: as in cost_to_tolerance.
Best best_of(const SceneRuns& scene, Group group, std::optional<int> round = std::nullopt);

/// Interleaved timing rounds of a scene: the most round_cpu entries of any run (0: none).
int timing_rounds(const SceneRuns& scene);

/// The best of group a over the best of group b (each at its best time), and its range over the
/// interleaved timing rounds (each round's bests against each other, and the ratio of the best
/// times, which may come from different rounds): the measured noise of the ratio.
struct Ratio {
  double value;
  std::optional<double> low, high;  ///< empty without interleaved rounds
  /// True when the range reaches both sides of `target`: the run cannot tell which side it is.
  bool straddles(double target) const { return low && high && *low <= target && target <= *high; }
};
std::optional<Ratio> best_ratio(const SceneRuns& scene, Group a, Group b);
/// The same for two runs of the scene: a's CPU time to the tolerance over b's.
std::optional<Ratio> run_ratio(const SceneRuns& scene, const SceneRuns::Run& a,
                               const SceneRuns::Run& b);

/// True when two runs of a scene integrate the same method: at two or more common step counts
/// the errors agree to 1e-4 (relative, where they are above round-off) and no common step count
/// disagrees. A CPU ratio between them is then runtime overhead alone.
bool same_method(const std::vector<Measurement>& a, const std::vector<Measurement>& b);

/// Mean fixed-point/Newton iterations per stage solve of a run; empty for explicit methods.
std::optional<double> mean_stage_iterations(const RunStats& stats);
/// Implicit stages per step of a method, from its runs (stage solves / steps); empty for
/// explicit methods or when no run completed.
std::optional<double> implicit_stages(const std::vector<Measurement>& runs);

/// Where a sweep stops working: the smallest step size that failed, the largest one below it that
/// ran, and why the first failed (all empty when no run failed).
struct Limit {
  std::optional<double> failed_h, stable_h;
  std::string why;
};
Limit stability_limit(const std::vector<Measurement>& sweep);

/// CPU time to the scaling tolerance of one line at size index i.
std::optional<double> scaling_cpu(const ScalingResult& result, size_t line, size_t i);

/// Index of the line of `group` cheapest at the largest size that any of them reached (the first
/// line of the group if none did); empty if the group has no line.
std::optional<size_t> best_line(const ScalingResult& result, Group group);

/// a / b when both are known.
std::optional<double> ratio(const std::optional<double>& a, const std::optional<double>& b);

}  // namespace ex
