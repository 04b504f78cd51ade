// The runs behind the charts and the summary: per problem, a sweep and an energy run per method;
// and the scaling scene (P1 for growing N, CPU time to reach 1e-6).
#pragma once

#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include "energy.hpp"
#include "problem.hpp"
#include "progress.hpp"
#include "sweep.hpp"

namespace ex {

/// The tolerances of P1-P3's comparisons.
inline constexpr double kTolerances[] = {1e-6, 1e-9};

/// What the report needs to know of a solver besides its runs.
struct SolverTraits {
  std::string name;
  Family family;
  bool from_paper;    ///< Solver::from_paper
  bool is_explicit;   ///< Solver::is_explicit
  bool exact_linear;  ///< Solver::exact_for_linear_part
  int order;
  std::string limit_of;  ///< Solver::limit_of
};
SolverTraits traits_of(const Solver& solver);

struct MethodResult : SolverTraits {
  std::optional<double> first_unstable_z;  ///< Solver::first_unstable_z
  std::vector<Measurement> sweep;
  EnergyCurve energy;
};

struct ProblemResult {
  std::string key, title;
  double t_error;
  Reference reference;
  std::vector<MethodResult> methods;
};

struct ScalingResult {
  std::vector<double> tolerances;  ///< compared at each; charted and tabled at the first
  double t_end;
  std::vector<int> sizes;
  std::vector<Reference> references;  ///< per size
  struct Line : SolverTraits {
    std::vector<std::vector<Measurement>> brackets;  ///< per size
  };
  std::vector<Line> lines;
};

struct RunConfig {
  SweepPolicy sweep;
  std::vector<long> steps;  ///< fixed step counts on [0, t_error]; empty: the paper's, extended
  std::vector<double> energy_t_ends{1, 10, 100, 1000};
  double reference_tolerance = 1e-14;
  std::vector<int> scaling_sizes{32, 128, 512, 2048};
  std::vector<double> scaling_tolerances{1e-6, 1e-9};
  double scaling_t_end = 1, scaling_reference_tolerance = 1e-12;
};

/// The sweeps and energy runs of every solver, then the runs that decide the comparisons at
/// `tolerances` timed again, interleaved (retime.hpp).
ProblemResult run_problem(const Problem& problem, const SolverList& solvers,
                          const RunConfig& config, Progress& progress,
                          const std::vector<double>& tolerances = {std::begin(kTolerances),
                                                                   std::end(kTolerances)});

/// `solvers`: the ERKN methods and peers to compare (the RKN limits are left out by the caller).
/// Per size, the runs that decide the comparisons are timed again, interleaved (retime.hpp).
ScalingResult run_scaling(const SolverList& solvers, const RunConfig& config, Progress& progress);

}  // namespace ex
