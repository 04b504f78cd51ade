// The interface of a stepper (one method, one step size, one System) and the choice between the
// two kinds: Stepper (stepper.hpp, implicit stages) and ExplicitStepper (explicit_stepper.hpp).
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "erkn/error.hpp"
#include "erkn/integrator.hpp"

namespace erkn::detail {

/// True when stage i's diagonal coefficient abar_ii is identically zero (the generator's closed
/// form is "0"): the stage is explicit, Q_i = r_i.
inline bool explicit_stage(const Method& method, int i) {
  const int s = method.stages();
  const char* form = method.table().closed_forms[2 * s + Coefficients::packed(i, i)];
  return form[0] == '0' && form[1] == '\0';
}

/// True when every stage is explicit: the method is a splitting of the exact linear flow and
/// kicks (docs/design.md §1).
inline bool explicit_stages(const Method& method) {
  for (int i = 0; i < method.stages(); ++i)
    if (!explicit_stage(method, i)) return false;
  return true;
}

/// Advances (q, p), held in M's eigen coordinates between steps (with their compensated-summation
/// errors); physical coordinates only where grad U is evaluated and when asked for.
class StepperBase {
 public:
  virtual ~StepperBase() = default;
  /// Replaces the state; forgets the stage history and the summation errors. A processed method
  /// applies pi^-1 here (its evaluations counted in stats); on error nothing changes.
  virtual void set_state(const Eigen::VectorXd& q, const Eigen::VectorXd& p, Statistics& stats) = 0;
  /// Writes the state in physical coordinates (a processed method's: pi of the kernel's state,
  /// counted in stats).
  virtual void get_state(Eigen::VectorXd& q, Eigen::VectorXd& p, Statistics& stats) = 0;
  /// One step (step_number 1-based and t at its start, for messages), counted into stats; on
  /// error the state and stats are unchanged.
  virtual void step(long step_number, double t, Statistics& stats) = 0;
  /// n steps, numbered from first, the k-th (0-based) from t = grid.ahead(k) (grid: the
  /// integrator's, at the first step's start), as n calls of step(); done counts those completed
  /// (on error: the ones before the step that failed, whose state and counts stay). A stepper
  /// overrides it to keep the loop out of the virtual call.
  virtual void steps(long n, long first, const TimeGrid& grid, Statistics& stats, long& done) {
    for (done = 0; done < n; ++done) step(first + done, grid.ahead(done), stats);
  }
  virtual void apply_M(const Eigen::VectorXd& x, Eigen::VectorXd& y) = 0;
  virtual System& system() = 0;
  /// A processed method's stepper (the explicit one: Method::add refuses a processor on an
  /// implicit table) saves everything its next steps read and change, which restore_kernel()
  /// puts back: Integrator::batch retakes a batch's steps from its start when pi fails at its
  /// end. Other steppers are never asked.
  virtual void save_kernel() {
    throw Error("save_kernel: the stepper of a method without a processor");
  }
  virtual void restore_kernel() {
    throw Error("restore_kernel: the stepper of a method without a processor");
  }
};

/// Dimensions up to this with M's identity eigenbasis (scalar, diagonal M; RKN methods) step with
/// the dimension as a compile-time constant.
inline constexpr Eigen::Index kFixedMaxD = 4;

/// The explicit steppers of the dimensions 1..kFixedMaxD in M's identity eigenbasis, and those in
/// a half-spectrum basis, with a gradient compiled into them (erkn/compiled_gradient.hpp,
/// instantiated where the user's gradient is known), which the runtime asks for in place of its own
/// (System::gradient) ones.
class CompiledSteppers {
 public:
  virtual ~CompiledSteppers() = default;
  /// The stepper of an explicit method for d <= kFixedMaxD, constructed as the runtime's own
  /// (ExplicitStepper's constructor); diagonal: one coefficient per coordinate (diagonal M), else
  /// one for all (scalar M, RKN methods).
  virtual std::unique_ptr<StepperBase> make(bool diagonal, const Method& method, System&& system,
                                            double h, const Options& options,
                                            const Eigen::VectorXd& lambda,
                                            Eigen::Index d) const = 0;
  /// The stepper of an explicit method in the half-spectrum basis of `axes` (circulant M, a
  /// periodic grid) with eigenvalues lambda, constructed as the runtime's own.
  virtual std::unique_ptr<StepperBase> make_half_spectrum(const Method& method, System&& system,
                                                          double h, const Options& options,
                                                          const std::vector<GridAxis>& axes,
                                                          const Eigen::VectorXd& lambda,
                                                          Eigen::Index d) const = 0;
};

}  // namespace erkn::detail
