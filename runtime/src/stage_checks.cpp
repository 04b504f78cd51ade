#include "stage_checks.hpp"

#include <string>

#include "erkn/error.hpp"
#include "format.hpp"

namespace erkn::detail {

namespace {
// "kick i of the processor pi of M (on the state at step N)".
std::string processor_kick(int i, const StepPlace& at) {
  return "kick " + std::to_string(i + 1) + " of the processor " + at.processor + " of " +
         std::string(at.method->name()) + " (on the state at step " + std::to_string(at.step) + ")";
}
}  // namespace

void non_finite_stage(int i, const StepPlace& at) {
  const std::string where =
      at.processor ? processor_kick(i, at)
                   : "step " + std::to_string(at.step) + " (t = " + format(at.t) + "): stage " +
                         std::to_string(i + 1) + " of " + std::string(at.method->name());
  throw Error(where +
              " is not finite (is h unstable for this problem? see erkn::advise_step_size); the "
              "state is unchanged");
}

void gradient_of_wrong_size(Eigen::VectorXd& g, Eigen::Index d, int i, const StepPlace& at,
                            const char* callback) {
  const Eigen::Index got = g.size();
  g.resize(d);
  throw Error("the " + std::string(callback) + " callback returned a vector of size " +
              std::to_string(got) + " for q of size " + std::to_string(d) + " (" +
              (at.processor
                   ? processor_kick(i, at)
                   : "step " + std::to_string(at.step) + ", stage " + std::to_string(i + 1)) +
              "); the state is unchanged");
}

void non_finite_gradient(int i, const StepPlace& at, const char* callback) {
  throw Error("the " + std::string(callback) + " callback returned a non-finite value at " +
              (at.processor ? processor_kick(i, at)
                            : "step " + std::to_string(at.step) + " (t = " + format(at.t) +
                                  "), stage " + std::to_string(i + 1)) +
              "; the state is unchanged");
}

void non_finite_result(bool q_ok, const StepPlace& at) {
  throw Error("step " + std::to_string(at.step) + " (t = " + format(at.t) + ") of " +
              std::string(at.method->name()) + " gives a non-finite " + (q_ok ? "p" : "q") +
              " (is h unstable for this problem? see erkn::advise_step_size); the state "
              "before the step is kept");
}

}  // namespace erkn::detail
