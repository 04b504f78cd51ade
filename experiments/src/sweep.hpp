// Step-size sweeps: the paper's step sizes, extended on both sides (by a factor 2, or sqrt 2 in a
// full run) until the error spans [error_low, error_high], the error stops falling, or the step
// count passes max_steps.
#pragma once

#include <vector>

#include "measure.hpp"

namespace ex {

struct SweepPolicy {
  double error_low = 1e-11, error_high = 1e-3;
  double factor = 2;        ///< ratio of successive step counts in the extensions
  long max_steps = 200000;  ///< on [0, t_end]
  TimingPolicy timing;
};

/// Measurements sorted by step count. `steps` non-empty: exactly those step counts, no extension.
std::vector<Measurement> sweep(const Solver& solver, const Problem& problem, double t_end,
                               const Vec& q_ref, const SweepPolicy& policy,
                               const std::vector<long>& steps);

/// Step counts bracketing every tolerance of `tolerances`: from `start`, halving until the error
/// is above the coarsest and doubling until it is within the finest (or max_steps / one step is
/// reached), one doubling beyond when doubling, and bisection between an unstable run and one
/// within the coarsest tolerance. Sorted by step count.
std::vector<Measurement> bracket(const Solver& solver, const Problem& problem, double t_end,
                                 const Vec& q_ref, const std::vector<double>& tolerances,
                                 long start, const SweepPolicy& policy);

}  // namespace ex
