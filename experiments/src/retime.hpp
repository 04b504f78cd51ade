// Interleaved re-timing of the runs that decide a scene's comparisons. A method and a peer timed
// minutes apart on a shared machine see different loads (other processes on the sibling hardware
// thread, in the caches): their ratio moved by ±30 % between two runs. So once a scene's sweeps
// are done, the runs that decide its best-against-best ratios are timed again, round-robin: in
// each round every contender's runs once, each round starting at the next contender. Their CPU
// time becomes the best of the rounds, and each round's own ratio gives the measured noise
// (summary.hpp: best_ratio).
#pragma once

#include <vector>

#include "summary.hpp"

namespace ex {

/// One method of a scene: the solver to run again, its traits and its measured runs.
struct TimedLine {
  const Solver* solver;
  const SolverTraits* traits;
  std::vector<Measurement>* runs;
};

/// A contender's CPU time to a tolerance is at most this factor above its group's best.
inline constexpr double kContenderMargin = 1.5;

/// Per tolerance and per Group, the contenders (and the registry methods that are the same
/// method as a contending peer, summary.hpp: same_method) have the runs their cost to the
/// tolerance is read from timed again in timing.rounds interleaved rounds; sets round_cpu, and
/// cpu to the rounds' minimum. `problem` is the scene's, as measured.
void retime_contenders(const Problem& problem, const std::vector<TimedLine>& lines,
                       const std::vector<double>& tolerances, const TimingPolicy& timing);

}  // namespace ex
