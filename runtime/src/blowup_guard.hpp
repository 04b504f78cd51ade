// The default blow-up guard (Options::blowup_guard): every kInterval steps the integrator
// measures its state; a measure beyond its limit stops the run with an erkn::Error and restores
// the state of the last check that passed.
//   With System::potential: the energy error |H - H_0| / scale, scale = 1/2 |p0|^2 + 1/2 q0^T M q0
//   + |U(q0)| (>= |H_0|; the sum of the energy's parts, so a sign change of H_0 cannot shrink it),
//   limit kEnergyLimit. A symplectic method off its unstable step sizes keeps this bounded and
//   small. The advisor's "runs clean" bound is 0.5 (README, "Resonances"); the limit is half of
//   it because a bounded resonant error oscillates between checks (with a limit of 0.5,
//   SERKN3s4pf(2) on FPU at h omega = 0.999 pi ran 1e5 steps unstopped with peaks of 0.54).
//   Without one: the quadratic energy E_2 = 1/2 |p|^2 + 1/2 q^T M q (the norm of the state in M's
//   eigenbasis) against its first positive value, limit kGrowthLimit: exponential growth crosses
//   it within a few checks, a bounded nonlinear exchange never does.
// A non-finite measure is always beyond the limit. The check costs one state transform, one
// product with M and (with a potential) one U per kInterval steps. The reference is measured when
// the first check needs it, from the checkpoint (the state the guard started at): a run shorter
// than kInterval steps pays nothing for the guard but the checkpoint's copy of the state.
// One mechanism for erkn::Integrator and the distributed erkn::mpi::GridIntegrator: each front
// end forms the measure's Sums (the latter summed over its ranks by one reduce, so every rank
// takes the same decision) and keeps its state in the checkpoint.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <string>

#include "erkn/advisor.hpp"
#include "erkn/error.hpp"
#include "erkn/integrator.hpp"

namespace erkn::detail {

class BlowupGuard {
 public:
  static constexpr long kInterval = 1024;
  static constexpr double kEnergyLimit = 0.25, kGrowthLimit = 1e4;

  /// The state a failed check returns to: the last one that passed.
  struct Checkpoint {
    Eigen::VectorXd q, p;
    TimeGrid grid{0.0, 1.0};  // (every start saves the integrator's)
    long steps = 0;
  };

  /// The parts of the measure at a state.
  struct Sums {
    double E2 = 0;  ///< 1/2 |p|^2 + 1/2 q^T M q
    double U = 0;   ///< U(q) where needs_potential, else 0
    double H() const { return E2 + U; }
    double scale() const { return E2 + std::abs(U); }
  };

  /// Starts over at a new state (construction, set_state), which the checkpoint saved next
  /// holds; its measure, the reference, is pending until set_reference.
  void start(bool on);
  /// True from start until set_reference.
  bool pending() const { return pending_; }
  /// Whether the next Sums need U(q): a potential is given and the reference is pending or the
  /// energy is watched.
  bool needs_potential(bool has_potential) const { return has_potential && (pending_ || energy_); }
  /// The reference from the state the guard started at: H = E_2 + U there (E_2 without a
  /// potential) and scale = E_2 + |U|. With a potential and H finite the energy is watched
  /// (H_0 = H), else E_2.
  void set_reference(double H, double scale, bool has_potential);
  /// The measure of a state: H = E_2 + U while the reference is pending or the energy is
  /// watched, else E_2.
  double measure(const Sums& s) const { return pending_ || energy_ ? s.H() : s.E2; }
  /// True once per kInterval calls (when on).
  bool due() { return due_after(1); }
  /// steps (<= until_due()) taken at once: true when due() would be after the last of them.
  bool due_after(long steps) {
    if (!on_ || (countdown_ -= steps) > 0) return false;
    countdown_ = kInterval;
    return true;
  }
  /// The steps until the next check (no bound when off).
  long until_due() const { return on_ ? countdown_ : std::numeric_limits<long>::max(); }
  /// The growth of `measure` against its reference, in units of the limit (> 1: a blow-up).
  double growth(double measure);
  bool on() const { return on_; }
  bool uses_energy() const { return energy_; }
  Checkpoint& checkpoint() { return checkpoint_; }
  /// A vector of size d for the check's product with M (allocated once).
  Eigen::VectorXd& workspace(Eigen::Index d) {
    if (workspace_.size() != d) workspace_.resize(d);
    return workspace_;
  }
  /// The error for a check that failed with `measure` at time t (step `step`), the checkpoint's
  /// time t_kept restored; `cause`: the advisor's verdict at h there (likely_cause).
  std::string message(double measure, double t, long step, double t_kept,
                      const std::string& cause) const;
  /// The message's likely cause: the step-size advisor's verdict `advise()` at h, at the kept
  /// state ("unknown" with the advisor's error when it cannot judge h).
  template <class Advise>
  static std::string likely_cause(Advise&& advise, const Method& method, double h) {
    try {
      return cause(advise(), method, h);
    } catch (const Error& e) {
      return std::string("unknown (the step-size advisor cannot judge h: ") + e.what() + ")";
    }
  }

 private:
  bool on_ = false, energy_ = false, pending_ = false;
  long countdown_ = kInterval;
  double reference_ = 0, scale_ = 0;
  Checkpoint checkpoint_;
  Eigen::VectorXd workspace_;

  static std::string cause(const StepSizeAdvice& advice, const Method& method, double h);
};

}  // namespace erkn::detail
