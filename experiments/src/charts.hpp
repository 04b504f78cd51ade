// gnuplot charts (PNG and SVG): per problem (i) error vs grad U evaluations, (ii) error vs CPU
// time, (iii) max|H_n - H_0| vs t_end, each once per group of methods (ChartGroup) so that no
// chart holds every method; and the scaling scene. Data and scripts go to
// <charts>/data/, so `cd <charts> && gnuplot data/<name>.gp` redraws one set.
#pragma once

#include <filesystem>
#include <string>

#include "experiment.hpp"
#include "summary.hpp"

namespace ex {

/// The registry's methods of one set of charts, drawn with every peer: the paper's methods
/// (file suffix "", e.g. p1_cpu.png), erkn's explicit methods ("_explicit") and its other
/// implicit methods ("_other").
struct ChartGroup {
  Group group;
  std::string suffix, title;
};
/// The groups with at least one of `methods` (the paper's group always, so its files exist).
std::vector<ChartGroup> chart_groups(const std::vector<MethodResult>& methods);

/// Writes data and script for one problem and runs gnuplot: per chart group,
/// <key><suffix>_{evals,cpu,energy}.{png,svg}.
void chart_problem(const ProblemResult& result, const std::filesystem::path& charts_dir);
void chart_scaling(const ScalingResult& result, const std::filesystem::path& charts_dir);
/// The stiff scene at one kappa, per chart group: <key><suffix>_cpu (error vs CPU time) and
/// <key><suffix>_h (error vs step size, with each method's failed runs drawn as crosses in a row
/// at error 1e3, and above them a triangle at the h where its linear stability bound on the V = 0
/// line, Solver::first_unstable_z, predicts the failure: h^2 kappa = z*).
void chart_stiff(const ProblemResult& result, double kappa,
                 const std::filesystem::path& charts_dir);

/// Runs `gnuplot <script>` in charts_dir (no shell); throws when gnuplot fails.
void run_gnuplot(const std::filesystem::path& charts_dir, const std::string& script);

/// Lower-case file-name form of a method or problem name ("SERKN3s4(1)" -> "serkn3s4_1").
std::string slug(const std::string& name);

}  // namespace ex
