// What the grid scenes measure, per scene: filled by grid_scenes.cpp size by size and written out
// by grid_report.cpp after every step, so that a run that stops keeps what it computed.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "grid_scenes.hpp"
#include "problem.hpp"

namespace ex {

/// One method at one size.
struct GridCell {
  bool ran = false;
  std::vector<Measurement> runs;
  std::optional<double> cpu, steps;  ///< to the tolerance (interpolated), when bracketed
  double predicted_steps = 0;        ///< what the order predicts for the tolerance (0: no run ok)
  std::string failure;               ///< an exception that ended the method's runs at this size
  std::string skipped;               ///< why it did not run here (empty when it ran)
};

struct GridLine {
  const Solver* solver;
  std::vector<GridCell> cells;  ///< per size, as far as the scene got
};

/// Time per step of one method against d, with the fit t = c d log2 d.
struct StepTimes {
  const Solver* solver = nullptr;
  double h = 0;                                ///< step size the times are taken at
  std::vector<std::optional<double>> seconds;  ///< per step size entry (empty: failed)
  std::vector<long> steps_timed;               ///< k of (best of 2k steps - best of k) / k
  double c = 0, deviation = 0, slope = 0;      ///< fit; max |t / fit - 1|; slope of log t
  std::optional<double> bytes_per_unknown;     ///< erkn::Integrator's memory (ERKN methods)
  std::string failure;
};

struct GridScene {
  std::string key, title;
  std::function<Problem(int)> make;
  std::vector<int> sizes, step_sizes;
  std::vector<long> dims, step_dims;  ///< as far as the scene got
  std::vector<Reference> references;  ///< per size done
  std::vector<GridLine> lines;
  std::vector<StepTimes> step_times;
  std::string failure;  ///< what stopped the scene early (empty: it finished)
  double wall = 0;      ///< seconds spent on it
};

/// Writes <out>/grids.md from the scenes as far as they got; `status` says whether the run
/// finished. `dense` holds (d, seconds) of the dense path's setup, when measured.
void write_grid_report(const std::filesystem::path& out, const std::vector<GridScene>& scenes,
                       const GridSceneConfig& config, const std::string& command,
                       const std::string& status, const std::vector<std::pair<int, double>>& dense);

/// Data, gnuplot script and <charts>/grid_<key>_{cpu,step}.{png,svg} of one scene.
void chart_grid_scene(const GridScene& scene, const std::filesystem::path& charts,
                      double tolerance);

}  // namespace ex
