// One measured run: error at t_end against a reference, counts, CPU time (best of repeats).
#pragma once

#include <string>
#include <vector>

#include "solver.hpp"

namespace ex {

struct Measurement {
  long steps = 0;
  double h = 0;
  double error = 0;  ///< max-norm of q(t_end) - reference; +inf when the run failed or blew up
  double cpu =
      0;  ///< seconds, best of the repeats (runs under 1 ms: per run of a batch), setup included
  /// Seconds per run in each round of an interleaved re-timing (retime.hpp), in round order;
  /// empty when the run was not re-timed. When present, cpu is their minimum.
  std::vector<double> round_cpu;
  RunStats stats;
  std::string failure;  ///< empty when the run succeeded
  bool ok() const { return failure.empty(); }
};

struct TimingPolicy {
  int repeats = 3;          ///< at most this many runs...
  double budget = 0.5;      ///< ...and no repeat once the runs so far took this many seconds,
  double min_total = 0.02;  ///< except that runs shorter than this in total repeat anyway
  /// Interleaved rounds of the re-timing of the runs that decide a comparison (retime.hpp)...
  int rounds = 5;
  /// ...each sample of which lasts at least this many seconds (short runs in a batch).
  double round_sample = 5e-3;
};

/// Integrates `problem` to t_end with `steps` steps and measures it against q_ref.
Measurement measure(const Solver& solver, const Problem& problem, double t_end, long steps,
                    const Vec& q_ref, const TimingPolicy& timing);

/// One more timing sample of a measured run (same problem, step and step count): CPU seconds
/// per run, a run shorter than `min_sample` seconds timed in a batch that lasts that long.
double time_again(const Solver& solver, const Problem& problem, const Measurement& m,
                  double min_sample);

/// CPU time of this process in seconds.
double cpu_seconds();

}  // namespace ex
