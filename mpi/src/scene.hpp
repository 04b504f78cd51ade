// The scene erkn-mpi runs: sine-Gordon (grad U = sin q) plus an optional mass shift on a tensor
// grid over [-1, 1] per axis, started from a Gaussian bump at rest; and its timing.
#pragma once

#include <mpi.h>

#include <string>
#include <vector>

#include "erkn/mpi.hpp"

namespace erkn::mpi::scene {

struct Settings {
  std::vector<GridAxis> axes;
  double shift = 0;
  std::string method = "SERKN2s4";
  double h = 1e-3;
  int steps = 20, repeats = 3;
  bool guard = true;  ///< Options::blowup_guard
};

/// Axes "256x256" with one boundary name for all ("periodic", "dirichlet", "neumann") or one per
/// axis ("periodic,dirichlet"); the spacing puts the grid on [-1, 1].
std::vector<GridAxis> parse_axes(const std::string& grid, const std::string& boundaries);
std::string describe(const std::vector<GridAxis>& axes);
/// The parts of s between the separators.
std::vector<std::string> split(const std::string& s, char sep);

struct Timing {
  int ranks = 1;
  long d = 0;
  double seconds_per_step = 0;            ///< best of the repeats, slowest rank
  double transform_seconds_per_step = 0;  ///< of that repeat, slowest rank
  double cpu_seconds_per_step = 0;        ///< process CPU time of that repeat, largest rank
  double transforms_per_step = 0, gradients_per_step = 0;
  double energy_drift = 0;       ///< |H(t) - H(0)| / |H(0)| at the end
  double sum_q = 0, norm_q = 0;  ///< of the final state (rank-count independent to round-off)
  double load = 0;               ///< the machine's 1-minute load average after the run
};

/// Integrates repeats x steps (after one warm-up step) and times each block (collective).
Timing run(MPI_Comm comm, const Settings& s);
/// The same scene through the serial library (erkn::Integrator, this process alone, step(steps)
/// and q() per block: the state loaded once, as the distributed run's integrate loads it): what
/// the distributed runs are measured against. Transforms are not counted (0).
Timing run_serial(const Settings& s);

}  // namespace erkn::mpi::scene
