// Reference q(t): the exact solution where known (P2), else the 13-stage Runge-Kutta-Fehlberg
// 7(8) method of Boost.Odeint with fixed steps on the first-order system (long double, or double
// where a looser reference suffices), its step halved until two successive results agree to
// `tolerance`.
#pragma once

#include <string>

#include "erkn/problems.hpp"

namespace erkn::problems {

struct Reference {
  Vec q;
  double accuracy = 0;  ///< max-norm difference between the last two halvings (0 if exact)
  long steps = 0;       ///< steps of the finest run (0 if exact)
  std::string method;   ///< how it was obtained, for the report
};

enum class Precision { long_double, double_ };

Reference reference_solution(const Problem& problem, double t_end, double tolerance,
                             Precision precision = Precision::long_double);

}  // namespace erkn::problems
