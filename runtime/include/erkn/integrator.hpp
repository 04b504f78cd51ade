// erkn::Integrator: a fixed-step ERKN (or RKN-limit) integrator for one System and step h.
//
// Each step is eq. (d) of the paper (the label in its LaTeX source; eq. 3 in print), V = h^2 M:
//   Q_i     = phi0(c_i^2 V) q + h c_i phi1(c_i^2 V) p - h^2 sum_{j<=i} abar_ij(V) g_j
//   q_{n+1} = phi0(V) q + h phi1(V) p - h^2 sum_i bbar_i(V) g_i
//   p_{n+1} = -h M phi1(V) q + phi0(V) p - h sum_i b_i(V) g_i
// with g_j = grad U(Q_j).
// RKN methods use V = 0 and g = M Q + grad U(Q) (their force is -M q - grad U(q)).
// The coefficients are evaluated once per (h, M) at each eigenvalue of M and applied in M's
// eigenbasis, where q and p stay between steps (q() and p() transform back on demand); a step
// allocates nothing (the Newton fallback allocates its workspace once).
//
// Explicit methods (every abar_ii identically 0) step as what they are: exact flows of
// q'' + M q = 0 alternated with kicks p -= h d_i g_i, the first kick reusing the previous step's
// last gradient when c_1 = 0 and c_s = 1 (FSAL).
//
// Implicit stage i solves Q = r_i - h^2 abar_ii(V) grad U(Q) by fixed-point iteration started
// from the stage gradients of the previous step and of this one extrapolated to c_i. It stops
// when theta/(1-theta) * |dQ| <= tolerance (theta: ratio of successive updates, |.| relative
// 2-norm), without a confirming evaluation; after one evaluation already when the contraction
// measured at an earlier solve of that stage (times 4, weighted by how g reaches q and p) proves
// it. If the iteration diverges or stalls, Newton's method takes over: for d <= 256 with a dense
// LU (user Hessian, else finite differences), beyond that matrix-free (GMRES on directional
// differences of grad U, preconditioned in M's eigenbasis). A stage that still fails throws
// erkn::Error and leaves the state unchanged.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <exception>
#include <memory>
#include <string>
#include <utility>

#include "erkn/method.hpp"
#include "erkn/system.hpp"
#include "erkn/time_grid.hpp"

namespace erkn {

namespace detail {
class StepperBase;
class BlowupGuard;
class CompiledSteppers;
}  // namespace detail

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
  /// Energy monitor: when > 0, a step after which |H_n - H_0| > energy_tolerance * |H_0| (H_0:
  /// the energy at construction or set_state; absolute when H_0 = 0) throws erkn::Error naming
  /// the step and the drift, and leaves the state before that step. Needs System::potential.
  double energy_tolerance = 0;
  /// Construction (and set_step_size) refuses an h that erkn::advise_step_size flags at the
  /// current state: a pole, or a trial run of 8192 steps that fails, whose energy error,
  /// extrapolated to 1e5 steps, reaches 0.25 (a resonance or an unstable band at h) or 0.5 / 16
  /// (none), or in which a quiet mode grows to take over within the run (see erkn/advisor.hpp,
  /// "Severity"); off by default.
  bool check_stability = false;
  /// Blow-up guard, on by default: every 1024 steps, a relative energy error |H - H_0| above 0.25
  /// (with System::potential; relative to 1/2|p0|^2 + 1/2 q0^T M q0 + |U(q0)|), else a 1e4-fold
  /// growth of 1/2|p|^2 + 1/2 q^T M q, or a non-finite state, throws erkn::Error naming the time,
  /// the growth and the step-size advisor's verdict at h, and restores the state of the last
  /// check that passed. Costs <= 2 % of a step (bench/). false switches it off (e.g. to measure
  /// how a run at an unstable h diverges).
  bool blowup_guard = true;
};

/// Throws erkn::Error naming the first field of `options` outside its range (the check every
/// Integrator and Ensemble runs on its Options; the Python Options runs it on every assignment).
void validate(const Options& options);

struct Statistics {
  long steps = 0;                 ///< accepted steps
  long gradient_evaluations = 0;  ///< calls of System::gradient (incl. finite differences)
  long hessian_evaluations = 0;   ///< calls of System::hessian
  /// modified forces grad(|grad U|^2) formed (modified kicks): calls of
  /// System::hessian_vector_product (or of System::hessian, also counted there, without it)
  long hessian_vector_products = 0;
  long stage_iterations = 0;   ///< fixed-point plus Newton iterations, over all stages
  long newton_fallbacks = 0;   ///< stages that fixed point could not solve
  long newton_iterations = 0;  ///< Newton iterations, over all fallbacks
  long state_loads = 0;        ///< transforms of the state back to physical coordinates after steps
  /// Processed methods (Method::is_processed): applications of the processor, pi^-1 when a
  /// state is set and pi when one is looked at (their gradients and Hessian-vector products are
  /// in the counts above).
  long processor_applications = 0;
  double wall_time = 0;  ///< seconds (steady clock) spent in integrate() and step(n) calls
  /// CPU seconds of the calling thread there (callbacks included). A call of less than
  /// Integrator::kCpuClockWork steps x dimension counts its wall time instead until it has lasted
  /// Integrator::kCpuClockDelay (0.1 ms) at an observer call (the 1st, 2nd, 4th, 8th, ... one of
  /// the call, once the coarse clock has ticked since it began: on Linux up to a tick, 1-4 ms,
  /// after the delay), and reads the thread CPU clock from then on: a clock read (a system call,
  /// ~2 us on a virtual machine) would cost more than its steps. So time an observer sleeps is
  /// not counted once the call has lasted that long and made twice the observer calls it had.
  double cpu_time = 0;
};

class Integrator {
 public:
  /// Validates everything (sizes, finiteness, h > 0, poles) and precomputes the coefficients
  /// for (h, M). The time starts at t0.
  Integrator(const Method& method, System system, double h, const Eigen::VectorXd& q0,
             const Eigen::VectorXd& p0, const Options& options = {}, double t0 = 0);
  /// The same with the explicit steppers of a small dimension (d <= 4, M's identity eigenbasis)
  /// from `compiled`, the gradient compiled into them: see erkn::make_integrator
  /// (erkn/compiled_gradient.hpp), which makes them; nullptr: as above. (The system by rvalue
  /// reference: the constructor above hands its own on without a move, 50 instructions at d = 1.)
  Integrator(const Method& method, System&& system, double h, const Eigen::VectorXd& q0,
             const Eigen::VectorXd& p0, const Options& options, double t0,
             std::shared_ptr<const detail::CompiledSteppers> compiled);
  ~Integrator();
  Integrator(Integrator&&) noexcept;
  Integrator& operator=(Integrator&&) noexcept;

  // A processed method (Method::is_processed) steps its kernel and shows pi of the kernel's
  // state: every call that steps (step, integrate) applies pi where it ends, as reading the state
  // would (q() and p() then reuse it; a loop of step() without reading the state pays a pi per
  // call that step(n) or integrate pays once), and refuses the step whose state pi maps to a
  // non-finite one, naming it, with the steps before it kept bit for bit. So q() and p() never
  // fail.

  /// One step of size h.
  void step();
  /// n >= 0 steps of size h, timed in statistics() (erkn::Error for n < 0, before any step).
  void step(long n);

  // Time semantics (erkn/time_grid.hpp). The integrator's grid is t0 + n h (t0: the start, or
  // the last set_state, set_step_size or off-grid integrate). A time within round-off of a grid
  // point (relative 4 eps of max(|t|, |t_end|, h): the error of forming t0 + n h) counts as that
  // grid point.

  /// Steps from t() to t_end and calls observer(t, q, p) after every `every`-th step of this call
  /// and after the last one. On the grid, t_end is reached by whole steps of h. Off the grid, the
  /// last step is a shorter one, of size t_end - t_n from the last grid point t_n before t_end,
  /// with the method's own coefficients at that step size: it is a step of the same symplectic
  /// method (exact for U = 0, no interpolation error), so t() == t_end afterwards and the grid
  /// restarts there. Validated before any step (t_end finite, not before t(), at most kMaxSteps
  /// steps, the shorter step clear of the method's poles); a failed step keeps the steps before.
  template <class Observer>
  void integrate(double t_end, Observer&& observer, long every = 1) {
    const TimeGrid::Plan plan = prepare_end(t_end, every);
    Timer timer(*this, plan.whole);
    for (long n = 0; n < plan.whole;) {  // (every steps at a time, the last batch shorter)
      const long batch = std::min(every, plan.whole - n);
      advance(batch);
      n += batch;
      if (batch == every || !plan.shorter) timer.before_observer(), observer(t(), q(), p());
    }
    if (plan.shorter) {
      step_to(t_end);
      timer.before_observer(), observer(t(), q(), p());
    }
  }
  /// Steps to t_end as above without an observer: the state stays in M's eigen coordinates
  /// (no transform back) until q() or p() asks for it.
  void integrate(double t_end) {
    const TimeGrid::Plan plan = prepare_end(t_end, 1);
    const Timer timer(*this, plan.whole);
    advance(plan.whole);
    if (plan.shorter) step_to(t_end);
  }
  /// Steps to t_end as integrate(t_end) does and calls observer(t, q, p) at each of `times`
  /// (ascending, within [t(), t_end]) with the state at that time from state_at: off-grid
  /// output does not move the grid, so the trajectory is the one without output. (At a grid
  /// point q and p are q() and p().)
  template <class Observer>
  void integrate(double t_end, const Eigen::Ref<const Eigen::VectorXd>& times,
                 Observer&& observer) {
    require_output_times(t_end, times);
    Timer timer(*this, prepare_end(t_end, 1).whole + long(times.size()));
    Eigen::VectorXd q, p;  // (the state between grid points; sized when first needed)
    for (double tau : times) {
      const bool on_grid = reach(tau);
      if (!on_grid) state_at(tau, q, p);
      timer.before_observer(), observer(tau, on_grid ? this->q() : q, on_grid ? this->p() : p);
    }
    integrate(t_end);
  }
  /// The state at t in [t(), t() + h] without changing the integrator: one step of size t - t()
  /// from the current state with the method's coefficients at that step size (the current state
  /// itself when t is t() up to round-off). Its error is the method's: O(h^order) globally, and
  /// it inherits the method's energy behaviour (measured in tests/runtime/output_test.cpp).
  /// Counts its gradient evaluations and iterations in statistics(), not in steps.
  void state_at(double t, Eigen::VectorXd& q, Eigen::VectorXd& p);

  /// Below this many steps x dimension, a call counts its wall time as CPU time until it has
  /// lasted kCpuClockDelay at an observer call (Statistics::cpu_time).
  static constexpr double kCpuClockWork = 16384;
  /// Seconds of wall time after which a short call with an observer reads the CPU clock.
  static constexpr double kCpuClockDelay = 1e-4;
  /// At most this many steps per integrate call: beyond 2^53 the grid t0 + n h is not exact.
  static constexpr double kMaxSteps = TimeGrid::kMaxSteps;

  /// Replaces the state (validated first; forgets the stage history used for starting guesses).
  void set_state(const Eigen::VectorXd& q, const Eigen::VectorXd& p, double t);
  /// Changes h (validated and tables recomputed first; on error nothing changes).
  void set_step_size(double h);

  /// The state in physical coordinates (the stepper keeps it in M's eigen coordinates; it is
  /// transformed back on the first call after a step).
  const Eigen::VectorXd& q() const {
    if (stale_) load_state();
    return q_;
  }
  const Eigen::VectorXd& p() const {
    if (stale_) load_state();
    return p_;
  }
  double t() const { return grid_.t(); }
  double h() const { return grid_.h(); }
  const Method& method() const { return method_; }
  const System& system() const;
  const Options& options() const { return options_; }
  const Statistics& statistics() const { return statistics_; }
  /// H(q, p) = 1/2 p^T p + 1/2 q^T M q + U(q); needs System::potential.
  double energy() const;
  /// H at another state (of this system's dimension), e.g. one from state_at.
  double energy(const Eigen::VectorXd& q, const Eigen::VectorXd& p) const;
  /// The number of whole steps of size h from t() towards t_end: t_end on the grid counts as
  /// reached, else the steps stop at the last grid point before t_end. erkn::Error if t_end is
  /// not finite, lies before t(), or needs more than kMaxSteps steps.
  long steps_until(double t_end) const { return grid_.plan_to(t_end).whole; }

 private:
  Method method_;
  Options options_;
  TimeGrid grid_;
  mutable Eigen::VectorXd q_, p_;  // the state in physical coordinates, current unless stale_
  mutable bool stale_ = false;
  // The blow-up guard's checkpoint state is q_, p_ (not copied) until they change.
  mutable bool checkpoint_in_state_ = false;
  mutable Statistics statistics_;  // (mutable: load_state counts state_loads)
  std::shared_ptr<const detail::CompiledSteppers> compiled_;  // (or nullptr)
  std::unique_ptr<detail::StepperBase> stepper_;
  // The stepper of the last step size other than h (a shorter last step, state_at), reused
  // while that size recurs.
  struct ShortStepper {
    std::unique_ptr<detail::StepperBase> stepper;
    double h = 0;
    Eigen::VectorXd q, p;  // its state after a step (step_to), the integrator's once accepted
  } short_;

  // Adds the wall and CPU time of its lifetime to statistics_ unless an outer Timer (a nested
  // integrate call) already does; a nested one reads no clock. A call of `steps` steps reads the
  // thread CPU clock from its start if steps x dimension >= kCpuClockWork; a shorter one counts
  // its wall time as CPU time until before_observer() finds it has lasted kCpuClockDelay (user
  // code that may sleep comes next), and reads the CPU clock from then on. before_observer()
  // looks at the coarse clock (coarse_wall_seconds, 9 ns) before the 1st, 2nd, 4th, 8th, ...
  // observer call only, and at the wall clock once the coarse one has ticked past the call's
  // start: a wall-clock read costs as much as a few steps at d = 1 (62 ns on the benchmark
  // machine; a Strang step on Duffing, construct + integrate of 2000 steps, 15-18 ns of thread
  // CPU time). So up to twice the observer calls made when the delay passed, and up to a tick of
  // the coarse clock after it, count too (an observer that sleeps a tick is caught at the next
  // check).
  class Timer {
   public:
    Timer(Integrator& run, long steps);
    ~Timer();
    Timer(const Timer&) = delete;
    Timer& operator=(const Timer&) = delete;
    void before_observer() {
      ++observer_calls_;
      // (the 1st, 2nd, 4th, 8th, ... call of a short call: inline, the rest a call less per
      // output time)
      if (run_ && !read_cpu_ && (observer_calls_ & (observer_calls_ - 1)) == 0) read_clocks();
    }

   private:
    void read_clocks();
    Integrator* run_;  // null when nested
    bool read_cpu_;
    long observer_calls_ = 0;
    double wall_0_, cpu_0_;
    double wall_as_cpu_ = 0;  // the wall time before the CPU clock was read
  };
  bool timing_ = false;

  void load_state() const;
  void load() const;  // (load_state's body)
  // t is t() up to round-off.
  bool is_now(double t) const { return std::abs(t - this->t()) <= grid_.tolerance(t); }
  // n steps of h (n calls of step()), in batches that end where the guard checks.
  void advance(long n);
  void batches(long n);  // (advance's body)
  void batch(long n);
  void take(long n, long& done);
  void processed_batch(long n);
  long keep_readable(long done, const Statistics& start, std::exception_ptr& failure);
  std::exception_ptr unreadable(long step, double t) const;
  bool took(long steps);  // steps taken: the state is stale, t() moves; true when the guard is due
  TimeGrid::Plan prepare_end(double t_end, long every);
  void require_output_times(double t_end, const Eigen::Ref<const Eigen::VectorXd>& times) const;
  void require_reachable(double t_out) const;
  // Steps to the last grid point at or before the output time tau (up to round-off: as
  // steps_until) and loads the state there (q(), p() current); true when tau is that point
  // (is_now).
  bool reach(double tau);
  detail::StepperBase& stepper_of_size(double h);
  void step_to(double t_end);
  // Energy monitor (Options::energy_tolerance > 0): H_0 and the state before the current step.
  struct EnergyMonitor {
    double H_0 = 0;
    Eigen::VectorXd saved_q, saved_p;
  } monitor_;
  void checked_step(detail::StepperBase& stepper);    // rolls back statistics, energy monitor
  void monitored_step(detail::StepperBase& stepper);  // (checked_step with the energy monitor)
  double monitored_energy(const Eigen::VectorXd& q, const Eigen::VectorXd& p) const;
  void check_energy(detail::StepperBase& stepper);
  // Blow-up guard (Options::blowup_guard).
  std::unique_ptr<detail::BlowupGuard> guard_;
  bool time_resolved_ = true;  // a step of h moves t() (TimeGrid::resolved; see step())
  double guard_measure(const Eigen::VectorXd& q, const Eigen::VectorXd& p, double* scale) const;
  void start_guard(const Eigen::VectorXd& q, const Eigen::VectorXd& p);
  void save_checkpoint();
  bool keep_checkpoint() const;
  void read_state(detail::StepperBase& stepper) const;
  std::pair<const Eigen::VectorXd&, const Eigen::VectorXd&> checkpoint_state() const;
  void start_guard_at_checkpoint();
  void check_guard(const char* failure = nullptr);
  std::string likely_cause() const;
};

}  // namespace erkn
