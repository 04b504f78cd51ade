#include "stiff_scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "retime.hpp"

namespace ex {

Problem stiff_sine_gordon(double kappa, double t_end) {
  constexpr int kN = 32;
  Problem p = sine_gordon(kN, kappa);
  char key[32];
  std::snprintf(key, sizeof key, "stiff_k%g", kappa);
  p.key = key;
  for (int i = 0; i < kN; ++i) p.q0[i] = std::sin(2 * std::numbers::pi * (i + 1) / kN);
  p.p0.setZero();
  p.t_error = t_end;
  // Seeds of the sweep on [0, t_end]: h = 1/8 (h^2 kappa = 156 at kappa = 1e4) to 1/256; the
  // sweep refines further until the error is small enough.
  p.paper_steps.clear();
  for (int n = 8; n <= 256; n *= 2) p.paper_steps.push_back(int(std::lround(n * t_end)));
  return p;
}

std::vector<StiffResult> run_stiff(const SolverList& solvers, const StiffConfig& stiff,
                                   const RunConfig& config, Progress& progress) {
  std::vector<StiffResult> out;
  for (double kappa : stiff.kappas) {
    const Problem problem = stiff_sine_gordon(kappa, stiff.t_end);
    ProblemResult r{problem.key, problem.title, problem.t_error, {}, {}};
    progress.label(problem.key + " reference");
    r.reference = reference_solution(problem, problem.t_error, config.reference_tolerance);
    progress.record(problem.key + " reference");
    // Coarser steps until the method fails (or one step is left), whatever the error: the scene
    // is about where each method stops working.
    SweepPolicy policy = config.sweep;
    policy.error_high = std::numeric_limits<double>::infinity();
    policy.error_low = 0.1 * *std::min_element(stiff.tolerances.begin(), stiff.tolerances.end());
    for (const auto& solver : solvers) {
      progress.label(problem.key + " " + solver->name());
      MethodResult m{traits_of(*solver), solver->first_unstable_z(), {}, {}};
      m.sweep = sweep(*solver, problem, problem.t_error, r.reference.q, policy, {});
      r.methods.push_back(std::move(m));
      progress.advance(problem.key + " " + solver->name());
    }
    progress.label(problem.key + " interleaved timing");
    std::vector<TimedLine> lines;
    for (size_t i = 0; i < solvers.size(); ++i)
      lines.push_back({solvers[i].get(), &r.methods[i], &r.methods[i].sweep});
    retime_contenders(problem, lines, stiff.tolerances, config.sweep.timing);
    progress.record(problem.key + " interleaved timing");
    out.push_back({kappa, stiff.tolerances, std::move(r)});
  }
  return out;
}

}  // namespace ex
