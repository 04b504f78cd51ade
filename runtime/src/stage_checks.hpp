// The checks every step makes around the user's gradient and on its result, shared by the
// implicit (stepper.hpp) and explicit (explicit_stepper.hpp) steppers: each failure is an
// erkn::Error naming the step, its time and the stage, and the state stays as it was.
#pragma once

#include <Eigen/Core>
#include <string>

#include "erkn/error.hpp"
#include "erkn/method.hpp"
#include "erkn/system.hpp"
#include "format.hpp"

namespace erkn::detail {

/// Where a step is: its number (1-based) and its time at the start, for messages.
struct StepPlace {
  const Method* method = nullptr;
  long step = 0;
  double t = 0;
};

/// g = grad U(Q) (0-based stage i) through System::gradient, counted in evaluations, refusing a
/// non-finite Q before the call, and a g of a size other than d or with a non-finite entry after.
inline void checked_gradient(const System& system, const Eigen::VectorXd& Q, Eigen::VectorXd& g,
                             Eigen::Index d, int i, const StepPlace& at, long& evaluations) {
  if (!Q.allFinite())
    throw Error("step " + std::to_string(at.step) + " (t = " + format(at.t) + "): stage " +
                std::to_string(i + 1) + " of " + std::string(at.method->name()) +
                " is not finite (is h unstable for this problem? see erkn::advise_step_size); "
                "the state is unchanged");
  system.gradient(Q, g);
  ++evaluations;
  if (g.size() != d) {
    const Eigen::Index got = g.size();
    g.resize(d);
    throw Error("the gradient callback returned a vector of size " + std::to_string(got) +
                " for q of size " + std::to_string(d) + " (step " + std::to_string(at.step) +
                ", stage " + std::to_string(i + 1) + "); the state is unchanged");
  }
  if (!g.allFinite())
    throw Error("the gradient callback returned a non-finite value at step " +
                std::to_string(at.step) + " (t = " + format(at.t) + "), stage " +
                std::to_string(i + 1) + "; the state is unchanged");
}

/// A step whose q_{n+1} or p_{n+1} would not be finite fails before it changes the state.
template <class Q, class P>
void require_finite_result(const Q& q_new, const P& p_new, const StepPlace& at) {
  const bool q_ok = q_new.allFinite();
  if (q_ok && p_new.allFinite()) return;
  throw Error("step " + std::to_string(at.step) + " (t = " + format(at.t) + ") of " +
              std::string(at.method->name()) + " gives a non-finite " + (q_ok ? "p" : "q") +
              " (is h unstable for this problem? see erkn::advise_step_size); the state "
              "before the step is kept");
}

}  // namespace erkn::detail
