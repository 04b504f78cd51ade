// Energy behaviour: max_n |H_n - H_0| over [0, t_end] for several t_end, from one run at fixed h.
#pragma once

#include <string>
#include <vector>

#include "solver.hpp"

namespace ex {

struct EnergyCurve {
  double h = 0;
  std::vector<double> t_end, max_error;  ///< equal lengths; max_error[i] over [0, t_end[i]]
  RunStats stats;                        ///< of the run to the largest t_end
  std::string failure;                   ///< empty when the run succeeded
};

/// One run to the largest t_end (ascending list); records the running maximum at each t_end.
EnergyCurve energy_errors(const Solver& solver, const Problem& problem, double h,
                          const std::vector<double>& t_ends);

}  // namespace ex
