// erkn::Integrator: a fixed-step ERKN (or RKN-limit) integrator for one System and step h.
//
// Each step is eq. (d) of the paper with V = h^2 M:
//   Q_i     = phi0(c_i^2 V) q + h c_i phi1(c_i^2 V) p - h^2 sum_{j<=i} abar_ij(V) g_j,  g_j = grad
//   U(Q_j) q_{n+1} = phi0(V) q + h phi1(V) p - h^2 sum_i bbar_i(V) g_i p_{n+1} = -h M phi1(V) q +
//   phi0(V) p - h sum_i b_i(V) g_i
// RKN methods use V = 0 and g = M Q + grad U(Q) (their force is -M q - grad U(q)).
// The coefficients are evaluated once per (h, M) at each eigenvalue of M and applied in M's
// eigenbasis; a step allocates nothing (the Newton fallback allocates its workspace once).
//
// Stage i solves Q = r_i - h^2 abar_ii(V) grad U(Q) by fixed-point iteration started from the
// previous step's stage gradients extrapolated to the new nodes (as GNI_IRK2 does). It stops when
// theta/(1-theta) * |dQ| <= tolerance (theta: ratio of successive updates, |.| relative 2-norm),
// without a confirming evaluation; the step uses the gradients already evaluated. If the
// iteration diverges or stalls, Newton's method takes over (user Hessian, else finite
// differences). A stage that still fails throws erkn::Error and leaves the state unchanged.
#pragma once

#include <Eigen/Core>
#include <memory>

#include "erkn/method.hpp"
#include "erkn/system.hpp"

namespace erkn {

namespace detail {
class StepperBase;
}

struct Options {
  /// Stage solver tolerance on theta/(1-theta)*|dQ|/|Q| (near round-off by default).
  double tolerance = 1e-14;
  /// An iteration that stops contracting with |dQ|/|Q| below this has reached round-off.
  double roundoff_level = 1e-12;
  /// Fixed-point iterations per stage before falling back to Newton.
  int max_fixed_point_iterations = 30;
  /// Contraction factor theta at or above which fixed point counts as stalled (-> Newton).
  double max_theta = 0.9;
  /// Newton iterations per stage before the step fails.
  int max_newton_iterations = 20;
  /// Kahan-compensated summation of q_{n+1} = q_n + dq and p_{n+1} = p_n + dp.
  bool compensated_summation = true;
  /// A step size is refused when some h^2*lambda lies within this relative distance of a pole.
  double pole_tolerance = 1e-6;
};

struct Statistics {
  long steps = 0;                 ///< accepted steps
  long gradient_evaluations = 0;  ///< calls of System::gradient (incl. finite differences)
  long hessian_evaluations = 0;   ///< calls of System::hessian
  long stage_iterations = 0;      ///< fixed-point plus Newton iterations, over all stages
  long newton_fallbacks = 0;      ///< stages that fixed point could not solve
  long newton_iterations = 0;     ///< Newton iterations, over all fallbacks
};

class Integrator {
 public:
  /// Validates everything (sizes, finiteness, h > 0, poles) and precomputes the coefficients
  /// for (h, M). The time starts at t = 0.
  Integrator(const Method& method, System system, double h, const Eigen::VectorXd& q0,
             const Eigen::VectorXd& p0, const Options& options = {});
  ~Integrator();
  Integrator(Integrator&&) noexcept;
  Integrator& operator=(Integrator&&) noexcept;

  /// One step of size h.
  void step();
  /// Steps to t_end, which must lie a whole number of steps ahead (else erkn::Error, nothing
  /// done); calls observer(t, q, p) after every step.
  template <class Observer>
  void integrate(double t_end, Observer&& observer) {
    for (long n = steps_until(t_end); n > 0; --n) {
      step();
      observer(t(), q(), p());
    }
  }
  void integrate(double t_end) {
    integrate(t_end, [](double, const Eigen::VectorXd&, const Eigen::VectorXd&) {});
  }

  /// Replaces the state (validated first; forgets the stage history used for starting guesses).
  void set_state(const Eigen::VectorXd& q, const Eigen::VectorXd& p, double t);
  /// Changes h (validated and tables recomputed first; on error nothing changes).
  void set_step_size(double h);

  const Eigen::VectorXd& q() const { return q_; }
  const Eigen::VectorXd& p() const { return p_; }
  double t() const { return t_base_ + double(steps_since_base_) * h_; }
  double h() const { return h_; }
  const Method& method() const { return method_; }
  const System& system() const;
  const Options& options() const { return options_; }
  const Statistics& statistics() const { return statistics_; }
  /// H(q, p) = 1/2 p^T p + 1/2 q^T M q + U(q); needs System::potential.
  double energy() const;
  /// The number of steps of size h from t() to t_end (erkn::Error unless a whole number).
  long steps_until(double t_end) const;

 private:
  Method method_;
  Options options_;
  double h_;
  Eigen::VectorXd q_, p_, q_error_, p_error_;  // state and its compensated-summation errors
  double t_base_ = 0;
  long steps_since_base_ = 0;
  Statistics statistics_;
  std::unique_ptr<detail::StepperBase> stepper_;
};

}  // namespace erkn
