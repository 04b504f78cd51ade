#include "experiment.hpp"

#include <cmath>

#include "retime.hpp"

namespace ex {

SolverTraits traits_of(const Solver& s) {
  return {s.name(),  s.family(),  s.from_paper(), s.is_explicit(), s.exact_for_linear_part(),
          s.order(), s.limit_of()};
}

ProblemResult run_problem(const Problem& problem, const SolverList& solvers,
                          const RunConfig& config, Progress& progress,
                          const std::vector<double>& tolerances) {
  ProblemResult out{problem.key, problem.title, problem.t_error, {}, {}};
  progress.label(problem.key + " reference");
  out.reference = reference_solution(problem, problem.t_error, config.reference_tolerance);
  progress.record(problem.key + " reference");
  for (const auto& solver : solvers) {
    progress.label(problem.key + " " + solver->name() + " sweep");
    MethodResult m{traits_of(*solver), solver->first_unstable_z(), {}, {}};
    m.sweep = sweep(*solver, problem, problem.t_error, out.reference.q, config.sweep, config.steps);
    progress.label(problem.key + " " + solver->name() + " energy");
    m.energy = energy_errors(*solver, problem, problem.h_energy, config.energy_t_ends);
    out.methods.push_back(std::move(m));
    progress.advance(problem.key + " " + solver->name());
  }
  progress.label(problem.key + " interleaved timing");
  std::vector<TimedLine> lines;
  for (size_t i = 0; i < solvers.size(); ++i)
    lines.push_back({solvers[i].get(), &out.methods[i], &out.methods[i].sweep});
  retime_contenders(problem, lines, tolerances, config.sweep.timing);
  progress.record(problem.key + " interleaved timing");
  return out;
}

ScalingResult run_scaling(const SolverList& solvers, const RunConfig& config, Progress& progress) {
  ScalingResult out{config.scaling_tolerances, config.scaling_t_end, config.scaling_sizes, {}, {}};
  for (const auto& solver : solvers) out.lines.push_back({traits_of(*solver), {}});
  for (int n : config.scaling_sizes) {
    Problem problem = sine_gordon(n);
    problem.t_error = config.scaling_t_end;
    progress.label("scaling N=" + std::to_string(n) + " reference");
    out.references.push_back(reference_solution(
        problem, config.scaling_t_end, config.scaling_reference_tolerance, Precision::double_));
    progress.record("scaling N=" + std::to_string(n) + " reference");
    for (size_t i = 0; i < solvers.size(); ++i) {
      progress.label("scaling N=" + std::to_string(n) + " " + solvers[i]->name());
      // Peers that resolve M's frequencies start at their stability limit h = 2/omega_max ~ 2/N;
      // methods exact for the linear part at h = 1/8.
      const bool resolves =
          solvers[i]->family() == Family::peer && !solvers[i]->exact_for_linear_part();
      const long start = resolves ? std::max(8L, long(n)) : 8L;
      out.lines[i].brackets.push_back(bracket(*solvers[i], problem, config.scaling_t_end,
                                              out.references.back().q, config.scaling_tolerances,
                                              start, config.sweep));
      progress.advance("scaling N=" + std::to_string(n) + " " + solvers[i]->name());
    }
    progress.label("scaling N=" + std::to_string(n) + " interleaved timing");
    std::vector<TimedLine> lines;
    for (size_t i = 0; i < solvers.size(); ++i)
      lines.push_back({solvers[i].get(), &out.lines[i], &out.lines[i].brackets.back()});
    retime_contenders(problem, lines, config.scaling_tolerances, config.sweep.timing);
    progress.record("scaling N=" + std::to_string(n) + " interleaved timing");
  }
  return out;
}

}  // namespace ex
