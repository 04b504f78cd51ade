// The large grid scenes (issue 10): 2-D periodic sine-Gordon and 3-D Dirichlet Klein-Gordon/phi^4
// on tensor grids. Per scene: CPU time to the tolerance against N for the ERKN methods and the
// peers that fit a large grid, time per step against d with its d log d fit, and the memory per
// unknown of the runtime's integrator. Writes <out>/grids.md and <out>/charts/grid_*.{png,svg}.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "solver.hpp"
#include "sweep.hpp"

namespace ex {

struct GridSceneConfig {
  std::vector<int> sg_sizes, kg_sizes;            ///< N for CPU time to tolerance
  std::vector<int> sg_step_sizes, kg_step_sizes;  ///< N for time per step against d
  std::vector<int> dense_sizes;                   ///< d for the dense path's setup time
  double tolerance = 1e-6;
  double reference_tolerance = 1e-7;  ///< agreement of the order-6 reference at n and 2n steps
  double line_budget = 5;  ///< s: a method whose predicted cost at the next N is more stops
  SweepPolicy sweep;
};

/// quick: 2-D up to 256^2, 3-D up to 64^3; full: 1024^2 and 128^3.
GridSceneConfig grid_scene_config(bool full, const SweepPolicy& sweep);

/// Runs both scenes with the grid-capable solvers among `solvers` (ERKN methods, Verlet, the
/// exact-flow splittings); `command` goes into the report. <out>/grids.md is rewritten after
/// every measurement, so a run that fails keeps what it computed; a failure (of a method, a
/// scene, or a chart) is recorded there. Returns false when anything failed.
bool run_grid_scenes(const GridSceneConfig& config, const SolverList& solvers,
                     const std::filesystem::path& out, const std::string& command);

}  // namespace ex
