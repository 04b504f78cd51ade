// gnuplot charts (PNG and SVG): per problem (i) error vs grad U evaluations, (ii) error vs CPU
// time, (iii) max|H_n - H_0| vs t_end; and the scaling scene. Data and scripts go to
// <charts>/data/, so `cd <charts> && gnuplot data/<name>.gp` redraws one set.
#pragma once

#include <filesystem>
#include <string>

#include "experiment.hpp"

namespace ex {

/// Writes data and script for one problem and runs gnuplot: <key>_{evals,cpu,energy}.{png,svg}.
void chart_problem(const ProblemResult& result, const std::filesystem::path& charts_dir);
void chart_scaling(const ScalingResult& result, const std::filesystem::path& charts_dir);
/// The stiff scene at one kappa: <key>_cpu (error vs CPU time) and <key>_h (error vs step size,
/// with each method's failed runs drawn as crosses on the top edge: where it becomes unstable).
void chart_stiff(const ProblemResult& result, const std::filesystem::path& charts_dir);

/// Runs `gnuplot <script>` in charts_dir (no shell); throws when gnuplot fails.
void run_gnuplot(const std::filesystem::path& charts_dir, const std::string& script);

/// Lower-case file-name form of a method or problem name ("SERKN3s4(1)" -> "serkn3s4_1").
std::string slug(const std::string& name);

}  // namespace ex
