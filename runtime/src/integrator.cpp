#include "erkn/integrator.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>

#include "blowup_guard.hpp"
#include "clock.hpp"
#include "erkn/advisor.hpp"
#include "erkn/error.hpp"
#include "explicit_stepper.hpp"
#include "format.hpp"
#include "modified_force.hpp"
#include "step_size_check.hpp"
#include "stepper.hpp"
#include "transforms.hpp"

namespace erkn {
namespace {

void require_sizes(const System& system, const Eigen::VectorXd& q, const Eigen::VectorXd& p) {
  if (q.size() == 0) throw Error("q is empty");
  if (p.size() != q.size())
    throw Error("dimension mismatch: q has size " + std::to_string(q.size()) + ", p has size " +
                std::to_string(p.size()));
  if (system.M.dim() != 0 && system.M.dim() != q.size())
    throw Error("dimension mismatch: M is " + std::to_string(system.M.dim()) + "x" +
                std::to_string(system.M.dim()) + ", q has size " + std::to_string(q.size()));
}

// The error for the first entry of q or p that is not finite (there is one).
Error non_finite_state(const Eigen::VectorXd& q, const Eigen::VectorXd& p) {
  Eigen::Index i = 0;
  while (std::isfinite(q[i]) && std::isfinite(p[i])) ++i;
  const bool in_q = !std::isfinite(q[i]);
  return Error(std::string(in_q ? "q[" : "p[") + std::to_string(i) +
               "] = " + format(in_q ? q[i] : p[i]) + " is not finite");
}

void require_state(const System& system, const Eigen::VectorXd& q, const Eigen::VectorXd& p) {
  require_sizes(system, q, p);
  if (!detail::all_finite(q.data(), q.size()) || !detail::all_finite(p.data(), p.size()))
    throw non_finite_state(q, p);
}

// require_state, with q and p copied to q_out, p_out in the pass that checks them (the
// constructor's: at N = 8192 the separate check was ~7 us of a construction).
void take_state(const System& system, const Eigen::VectorXd& q, const Eigen::VectorXd& p,
                Eigen::VectorXd& q_out, Eigen::VectorXd& p_out) {
  require_sizes(system, q, p);
  q_out.resize(q.size()), p_out.resize(p.size());
  const bool finite = detail::copy_finite(q.data(), q_out.data(), q.size());
  if (!detail::copy_finite(p.data(), p_out.data(), p.size()) || !finite)
    throw non_finite_state(q, p);
}

// Circulant M: the explicit Fourier basis (folded matrix-vector products, O(N^2)) up to N =
// kFourierBasisMaxN, beyond it the real FFT's half spectrum (FFTW's r2c, or else Eigen's); every
// method built with FFTW uses it from N = kFftwMinN on. Thread CPU time per step (median of 15 x
// 2000 steps, sine-Gordon, h = 0.8/N), basis vs FFTW: SABA2 N = 4 289 vs 217 ns, N = 32 1415 vs
// 1139 ns, N = 64 3064 vs 2276 ns; SERKN3s4(1) N = 4 1025 vs 775 ns, N = 32 2573 vs 2091 ns,
// N = 64 5560 vs 4066 ns. Implicit methods kept the basis until the stage solver's checks agreed
// (StructureAgreement: circulant and dense within 1e-13 over 50 steps, every method); with FFTW
// their CPU per grad U on sine-Gordon N = 32 fell from 700-760 to 575-640 ns (construct +
// integrate, 100 steps, h = 1/40; processes alternated on a loaded machine).
// Basis vs Eigen's FFT (erkn_step_benchmark, BM_StepCirculant, SERKN3s4(1)): N = 32 5.9 vs
// 6.1 us, N = 64 12.5 vs 13.3 us, N = 128 35 vs 24 us.
constexpr Eigen::Index kFftwMinN = 4, kFourierBasisMaxN = 64;

// Stepper S<Transform, Coef, D> for the dimension d: D = d when fixed sizes apply, else dynamic;
// args: the constructor's arguments before d.
template <template <class, class, int> class S, class Transform, class Coef, int D = 1,
          class... Args>
std::unique_ptr<detail::StepperBase> stepper_for(Eigen::Index d, Args&&... args) {
  if constexpr (std::is_same_v<Transform, detail::IdentityTransform> && D <= detail::kFixedMaxD) {
    if (d == D) return std::make_unique<S<Transform, Coef, D>>(std::forward<Args>(args)..., d);
    return stepper_for<S, Transform, Coef, D + 1>(d, std::forward<Args>(args)...);
  }
  return std::make_unique<S<Transform, Coef, Eigen::Dynamic>>(std::forward<Args>(args)..., d);
}

// The stepper of the method's kind over the eigenbasis Transform with coefficients Coef.
template <class Transform, class Coef, class... Args>
std::unique_ptr<detail::StepperBase> stepper_of(bool explicit_method, Eigen::Index d,
                                                Args&&... args) {
  if (explicit_method)
    return stepper_for<detail::ExplicitStepper, Transform, Coef>(d, std::forward<Args>(args)...);
  return stepper_for<detail::Stepper, Transform, Coef>(d, std::forward<Args>(args)...);
}

// The stepper in M's identity eigenbasis (RKN methods; scalar, diagonal M: Coef double,
// Eigen::ArrayXd): an explicit one of a fixed dimension from `compiled` when given.
template <class Coef>
std::unique_ptr<detail::StepperBase> identity_stepper(bool explicit_method,
                                                      const detail::CompiledSteppers* compiled,
                                                      const Method& method, System&& system,
                                                      double h, const Options& options,
                                                      const Eigen::VectorXd& lambda,
                                                      Eigen::Index d) {
  using detail::IdentityTransform;
  if (compiled && explicit_method && d <= detail::kFixedMaxD)
    return compiled->make(std::is_same_v<Coef, Eigen::ArrayXd>, method, std::move(system), h,
                          options, lambda, d);
  return stepper_of<IdentityTransform, Coef>(explicit_method, d, method, std::move(system), h,
                                             options, IdentityTransform{}, lambda);
}

// The stepper in the half-spectrum basis of `axes` (circulant M, a periodic grid): an explicit
// one from `compiled` when given.
std::unique_ptr<detail::StepperBase> half_spectrum_stepper(
    bool explicit_method, const detail::CompiledSteppers* compiled, const Method& method,
    System&& system, double h, const Options& options, const std::vector<GridAxis>& axes,
    const Eigen::VectorXd& lambda, Eigen::Index d) {
  using detail::HalfSpectrumTransform;
  if (compiled && explicit_method)
    return compiled->make_half_spectrum(method, std::move(system), h, options, axes, lambda, d);
  return stepper_of<HalfSpectrumTransform, Eigen::ArrayXd>(explicit_method, d, method,
                                                           std::move(system), h, options,
                                                           HalfSpectrumTransform(axes), lambda);
}

// compiled: the explicit steppers with the user's gradient compiled in (a fixed dimension, a
// half-spectrum basis), or nullptr (erkn/compiled_gradient.hpp).
std::unique_ptr<detail::StepperBase> make_stepper(const Method& method, System&& system, double h,
                                                  const Options& options, Eigen::Index d,
                                                  const detail::CompiledSteppers* compiled) {
  using namespace detail;
  check_step_size(method, h, system.M.eigenvalues(), options.pole_tolerance);
  // (A reference, not a copy: the stepper takes the system over with M's shared data, where
  // lambda, the axes and the transforms' matrices stay; a copy cost a count up and down.)
  const Stiffness& M = system.M;
  const Eigen::VectorXd& lambda = M.eigenvalues();
  const bool x = explicit_stages(method);
  if (method.has_modified_kicks() && !x)  // (Method::add refuses such tables)
    throw Error(std::string(method.name()) + ": modified kicks in an implicit method");
  if (method.kind() == Kind::rkn)
    return identity_stepper<double>(x, compiled, method, std::move(system), h, options,
                                    Eigen::VectorXd::Zero(1), d);
  switch (M.structure()) {
    case Stiffness::Structure::scalar:
      return identity_stepper<double>(x, compiled, method, std::move(system), h, options, lambda,
                                      d);
    case Stiffness::Structure::diagonal:
      return identity_stepper<Eigen::ArrayXd>(x, compiled, method, std::move(system), h, options,
                                              lambda, d);
    case Stiffness::Structure::dense:
      return stepper_of<OrthogonalTransform, Eigen::ArrayXd>(
          x, d, method, std::move(system), h, options, OrthogonalTransform{&M.eigenvectors()},
          lambda);
    case Stiffness::Structure::circulant: {
      const std::vector<GridAxis> axis{{d, 1.0, GridAxis::Boundary::periodic}};
      if (d < (grid_backend_is_fftw() ? kFftwMinN : kFourierBasisMaxN + 1) ||
          !half_spectrum_available(axis))
        return stepper_of<FourierBasisTransform, Eigen::ArrayXd>(
            x, d, method, std::move(system), h, options, FourierBasisTransform(d),
            FourierBasisTransform::coordinate_eigenvalues(lambda, d));
      return half_spectrum_stepper(x, compiled, method, std::move(system), h, options, axis, lambda,
                                   d);
    }
    case Stiffness::Structure::grid:
      if (half_spectrum_available(M.axes()))
        return half_spectrum_stepper(x, compiled, method, std::move(system), h, options, M.axes(),
                                     half_spectrum_eigenvalues(M.axes(), M.shift()), d);
      return stepper_of<GridTransform, Eigen::ArrayXd>(x, d, method, std::move(system), h, options,
                                                       GridTransform(M.axes()), lambda);
  }
  throw Error("unknown structure of M");
}

// Options::check_stability: refuses h when the step-size advisor flags it at (q, p).
void require_advised(const Method& method, const System& system, double h, const Eigen::VectorXd& q,
                     const Eigen::VectorXd& p) {
  const StepSizeAdvice advice = advise_step_size(method, system, h, q, p);
  if (!advice.safe()) throw Error("Options::check_stability refuses " + advice.report(method));
}

}  // namespace

Integrator::Integrator(const Method& method, System system, double h, const Eigen::VectorXd& q0,
                       const Eigen::VectorXd& p0, const Options& options, double t0)
    : Integrator(method, std::move(system), h, q0, p0, options, t0, nullptr) {}

Integrator::Integrator(const Method& method, System&& system, double h, const Eigen::VectorXd& q0,
                       const Eigen::VectorXd& p0, const Options& options, double t0,
                       std::shared_ptr<const detail::CompiledSteppers> compiled)
    : method_(method),
      options_(options),
      grid_(t0, h),  // (validates h and t0)
      compiled_(std::move(compiled)),
      // (default-initialised by its members' initialisers: make_unique value-initialised it,
      // zeroing the object first with a rep stos)
      guard_(std::make_unique_for_overwrite<detail::BlowupGuard>()) {
  validate(options);
  take_state(system, q0, p0, q_, p_);
  if (!system.gradient) throw Error("System::gradient is not set");
  detail::require_modified_force(method, system);
  if (options.energy_tolerance > 0 && !system.potential)
    throw Error("Options::energy_tolerance (the energy monitor) needs System::potential");
  if (options.check_stability) require_advised(method, system, h, q0, p0);
  stepper_ = make_stepper(method, std::move(system), h, options, q0.size(), compiled_.get());
  monitor_.H_0 = monitored_energy(q0, p0);
  guard_->start(options.blowup_guard);  // (its reference, at the checkpoint: when first needed)
  stepper_->set_state(q_, p_, statistics_);
  save_checkpoint();
}

Integrator::~Integrator() = default;
Integrator::Integrator(Integrator&&) noexcept = default;
Integrator& Integrator::operator=(Integrator&&) noexcept = default;

const System& Integrator::system() const { return stepper_->system(); }

// (Inline: a call of its own cost ~15 instructions per step() at d = 1.)
inline bool Integrator::took(long steps) {
  stale_ = stale_ || steps > 0;
  grid_.advance(steps);
  return guard_->due_after(steps);
}

// (Inline, the monitor out of line: callgrind, Duffing Strang by step(): 31 -> ~10 instructions
// per step.)
inline void Integrator::checked_step(detail::StepperBase& stepper) {
  if (options_.energy_tolerance > 0) return monitored_step(stepper);
  stepper.step(statistics_.steps + 1, t(), statistics_);
}

// The batch's n steps; done: those completed (on error: the ones before the step that failed).
inline void Integrator::take(long n, long& done) {
  // One step (step(), the energy monitor's batches): the stepper's step(), without the loop
  // of steps() (callgrind, Duffing Strang by step(): 331 -> 287 instructions per step).
  if (n == 1)
    checked_step(*stepper_), done = 1;
  else
    stepper_->steps(n, statistics_.steps + 1, grid_, statistics_, done);
}

// n steps, as many calls of step() (n <= the guard's steps until its check): the stepper loops
// over them (StepperBase::steps), so a step costs no call through the integrator.
// (Always inline in step() and batches(): reach -> advance -> batch was three frames per output
// time, 105 instructions at d = 1; callgrind, Duffing Strang with 20 output times.)
[[gnu::always_inline]] inline void Integrator::batch(long n) {
  // (Known at every restart of the grid and at every guard check: stepping alone needs ~1e14
  // steps to leave the resolved range.)
  if (!time_resolved_) grid_.require_resolved();
  if (method_.is_processed()) return processed_batch(n);
  long done = 0;
  try {
    take(n, done);
  } catch (const Error& e) {  // (a blow-up often ends in a failed stage: say so)
    took(done);               // (no check due: fewer steps than until_due())
    if (guard_->on()) check_guard(e.what());
    throw;
  } catch (...) {  // (e.g. the user's gradient's own exception: the steps before it stay)
    took(done);
    throw;
  }
  if (took(n)) check_guard();
}

// (advance(1) is one batch: the guard's countdown never falls below one step.)
void Integrator::step() { batch(1); }

void Integrator::step(long n) {
  if (n < 0) throw Error("step(n): n must be >= 0; got " + std::to_string(n));
  const Timer timer(*this, n);
  advance(n);
}

// (Always inline in reach and advance: with reach -> advance a frame per output time; callgrind,
// Duffing Strang with 20 output times.)
[[gnu::always_inline]] inline void Integrator::batches(long n) {
  // (The energy monitor checks every step: batches of one.)
  const long most = options_.energy_tolerance > 0 ? 1 : std::numeric_limits<long>::max();
  while (n > 0) {
    const long k = std::min({n, most, guard_->until_due()});
    batch(k);
    n -= k;
  }
}

void Integrator::advance(long n) { batches(n); }

// A processed method's batch (psi = pi o K o pi^-1: the stepper steps the kernel K) is accepted
// with the state a user sees, pi of the kernel's: pi is applied where the batch ends (load_state,
// whose q_, p_ q() and p() then return: on a good run nothing is computed that reading the state
// would not compute), and a batch whose steps' states pi maps to a non-finite one keeps only the
// steps before the first such (keep_readable). So q() and p() never fail, and the error names
// the step. Otherwise as batch(): the guard's check on an erkn::Error, the steps kept counted.
void Integrator::processed_batch(long n) {
  const Statistics start = statistics_;
  stepper_->save_kernel();
  long done = 0;
  std::exception_ptr failure;
  try {
    take(n, done);
  } catch (...) {
    failure = std::current_exception();
  }
  done = keep_readable(done, start, failure);
  const bool due = took(done);
  stale_ = false;  // (q_, p_: pi of the state kept)
  if (!failure) {
    if (due) check_guard();
    return;
  }
  try {
    std::rethrow_exception(failure);
  } catch (const Error& e) {
    if (guard_->on()) check_guard(e.what());
    throw;
  }
}

// pi of the state after the `done` steps of the batch that began at statistics `start` (its
// kernel's state saved), into q_, p_. If pi's image is not finite (or pi fails otherwise), the
// steps are retaken from the batch's start one at a time, each followed by pi: the run keeps
// those before the first that fails, bit for bit the batch's (the same arithmetic from the same
// saved state), counted with the processor applications that read them; `failure` becomes that
// step's error. Returns the number of steps kept. (The energy monitor has read the state: its
// batches are one checked_step.)
long Integrator::keep_readable(long done, const Statistics& start, std::exception_ptr& failure) {
  if (done == 0 || options_.energy_tolerance > 0) return done;
  try {
    load_state();
    return done;
  } catch (...) {
  }
  stepper_->restore_kernel();
  statistics_ = start;
  for (long k = 0; k < done; ++k) {
    stepper_->save_kernel();
    const Statistics before = statistics_;
    try {
      stepper_->step(start.steps + k + 1, grid_.ahead(k), statistics_);
      load_state();
    } catch (...) {
      stepper_->restore_kernel();
      statistics_ = before;
      failure = unreadable(start.steps + k + 1, grid_.ahead(k));
      return k;
    }
  }
  return done;  // (pi failed once and not again: a gradient that is not a function of q)
}

// The error of step `step` (from t) on whose state the processor failed, from the current
// exception: an erkn::Error says so, naming the step; the user's own exception is passed on.
std::exception_ptr Integrator::unreadable(long step, double t) const {
  try {
    throw;
  } catch (const Error& e) {
    return std::make_exception_ptr(
        Error("step " + std::to_string(step) + " (t = " + format(t) + ") of " +
              std::string(method_.name()) +
              " is refused, the state before it kept: the processor fails on the state after it (" +
              e.what() + "); is h unstable for this problem? see erkn::advise_step_size"));
  } catch (...) {
    return std::current_exception();
  }
}

using detail::coarse_wall_seconds;
using detail::cpu_seconds;
using detail::wall_seconds;

Integrator::Timer::Timer(Integrator& run, long steps)
    : run_(run.timing_ ? nullptr : &run),
      read_cpu_(double(steps) * double(run.q_.size()) >= kCpuClockWork),
      wall_0_(run_ ? wall_seconds() : 0),
      cpu_0_(run_ && read_cpu_ ? cpu_seconds() : 0) {
  run.timing_ = true;
}

void Integrator::Timer::read_clocks() {
  // (The coarse clock never leads: until it has ticked past the call's start, less than a tick
  // has passed. After a tick, the wall clock decides.)
  if (coarse_wall_seconds() <= wall_0_) return;
  const double wall = wall_seconds() - wall_0_;
  if (wall < kCpuClockDelay) return;
  read_cpu_ = true;
  wall_as_cpu_ = wall;
  cpu_0_ = cpu_seconds();
}

Integrator::Timer::~Timer() {
  if (!run_) return;
  const double wall = wall_seconds() - wall_0_;
  run_->statistics_.wall_time += wall;
  run_->statistics_.cpu_time += read_cpu_ ? wall_as_cpu_ + cpu_seconds() - cpu_0_ : wall;
  run_->timing_ = false;
}

// (The stepper counts nothing for a step that fails.)
void Integrator::monitored_step(detail::StepperBase& stepper) {
  monitor_.saved_q = q(), monitor_.saved_p = p();
  const Statistics before = statistics_;
  stepper.step(statistics_.steps + 1, t(), statistics_);
  try {
    check_energy(stepper);
  } catch (...) {  // (also an exception from System::potential: the step did not happen)
    statistics_ = before;
    stepper.set_state(monitor_.saved_q, monitor_.saved_p, statistics_);
    q_.swap(monitor_.saved_q), p_.swap(monitor_.saved_p);
    stale_ = false;
    throw;
  }
}

double Integrator::monitored_energy(const Eigen::VectorXd& q, const Eigen::VectorXd& p) const {
  if (options_.energy_tolerance <= 0) return 0;
  const double H = energy(q, p);
  if (!std::isfinite(H))
    throw Error("the energy monitor needs a finite H at the initial state; got H = " + format(H));
  return H;
}

// The energy monitor after a step of `stepper`: beyond the tolerance the step is an error (and
// checked_step restores the state before it, dropping its compensated-summation errors).
void Integrator::check_energy(detail::StepperBase& stepper) {
  read_state(stepper);
  stale_ = false;
  const double H = energy(q_, p_), scale = monitor_.H_0 == 0 ? 1.0 : std::abs(monitor_.H_0);
  const double drift = std::abs(H - monitor_.H_0) / scale;
  if (drift <= options_.energy_tolerance) return;  // (false for NaN)
  throw Error("energy monitor: step " + std::to_string(statistics_.steps) +
              " (from t = " + format(t()) + ") gives H = " + format(H) + ", |H - H_0| " +
              (monitor_.H_0 == 0 ? "= " : "/ |H_0| = ") + format(drift, 3) +
              " > Options::energy_tolerance = " + format(options_.energy_tolerance, 3) +
              " (H_0 = " + format(monitor_.H_0) + "); the state before the step is kept");
}

// Before q_, p_ change: the checkpoint's state they hold moves into the checkpoint (a swap, no
// copy: the checkpoint's previous vectors, resized, become q_ and p_). True when it moved.
[[gnu::always_inline]] inline bool Integrator::keep_checkpoint() const {
  if (!checkpoint_in_state_) return false;
  detail::BlowupGuard::Checkpoint& c = guard_->checkpoint();
  c.q.swap(q_), c.p.swap(p_);
  q_.resize(c.q.size()), p_.resize(c.p.size());
  checkpoint_in_state_ = false;
  return true;
}

// stepper's state into q_, p_ (the checkpoint they hold kept first); when get_state fails (a
// processed method's pi) q_, p_ and the checkpoint in them are as they were.
[[gnu::always_inline]] inline void Integrator::read_state(detail::StepperBase& stepper) const {
  const bool kept = keep_checkpoint();
  try {
    stepper.get_state(q_, p_, statistics_);
  } catch (...) {
    if (kept) {
      detail::BlowupGuard::Checkpoint& c = guard_->checkpoint();
      c.q.swap(q_), c.p.swap(p_);
      checkpoint_in_state_ = true;
    }
    throw;
  }
}

// (Always inline in reach and load_state: the output path's load without a call of its own.)
[[gnu::always_inline]] inline void Integrator::load() const {
  read_state(*stepper_);
  ++statistics_.state_loads;
  stale_ = false;
}

void Integrator::load_state() const { load(); }

void Integrator::set_state(const Eigen::VectorXd& q, const Eigen::VectorXd& p, double t) {
  require_state(system(), q, p);
  if (q.size() != q_.size())  // (a scalar M fits any dimension, the integrator only its own)
    throw Error("dimension mismatch: the integrator was built for dimension " +
                std::to_string(q_.size()) + ", the new q has size " + std::to_string(q.size()));
  const TimeGrid grid = grid_.with_start(t);  // (validates t)
  monitor_.H_0 = monitored_energy(q, p);
  guard_->start(options_.blowup_guard);
  stepper_->set_state(q, p, statistics_);
  q_ = q;
  p_ = p;
  stale_ = false;
  grid_ = grid;
  save_checkpoint();
}

void Integrator::set_step_size(double h) {
  const TimeGrid grid = grid_.with_step(h);  // (validates h)
  if (options_.check_stability) require_advised(method_, system(), h, q(), p());
  auto fresh = make_stepper(method_, System(system()), h, options_, q_.size(), compiled_.get());
  fresh->set_state(q(), p(), statistics_);  // (the summation errors are dropped)
  grid_ = grid;
  stepper_ = std::move(fresh);
  if (guard_->pending()) start_guard_at_checkpoint();
  save_checkpoint();  // (on the grid of h; the guard's reference measured before, at the start)
}

TimeGrid::Plan Integrator::prepare_end(double t_end, long every) {
  if (every < 1)
    throw Error("the observer interval must be >= 1 step; got " + std::to_string(every));
  const TimeGrid::Plan plan = grid_.plan_to(t_end);
  // (validates the shorter step, poles, before any step)
  if (plan.shorter) stepper_of_size(t_end - grid_.ahead(plan.whole));
  return plan;
}

detail::StepperBase& Integrator::stepper_of_size(double h) {
  if (!short_.stepper || short_.h != h) {
    try {
      short_.stepper =
          make_stepper(method_, System(system()), h, options_, q_.size(), compiled_.get());
    } catch (const Error& e) {
      short_.stepper.reset();
      throw Error("a step of size " + format(h, 17) + " (to a time off the grid of h = " +
                  format(grid_.h(), 17) + ") is refused: " + e.what());
    }
    short_.h = h;
  }
  short_.stepper->set_state(q(), p(), statistics_);  // (its last use started from another state)
  return *short_.stepper;
}

// (A processed method's pi after the step, or pi^-1 before the next, may fail: then nothing
// changes, the step's counts included.)
void Integrator::step_to(double t_end) {
  detail::StepperBase& s = stepper_of_size(t_end - t());
  const Statistics before = statistics_;
  checked_step(s);
  short_.q.resize(q_.size()), short_.p.resize(q_.size());  // (allocated once)
  try {
    s.get_state(short_.q, short_.p, statistics_);
    stepper_->set_state(short_.q, short_.p, statistics_);  // (the next step of h does not follow
  } catch (...) {                                          // a step of h)
    statistics_ = before;
    std::rethrow_exception(unreadable(before.steps + 1, t()));
  }
  keep_checkpoint();
  q_.swap(short_.q), p_.swap(short_.p);
  grid_.restart(t_end);
  time_resolved_ = grid_.resolved();
  if (guard_->due()) check_guard();
}

void Integrator::state_at(double t_out, Eigen::VectorXd& q, Eigen::VectorXd& p) {
  if (!std::isfinite(t_out)) throw Error("state_at(" + format(t_out) + "): t is not finite");
  const double t0 = t(), tol = grid_.tolerance(t_out);
  if (!(t_out >= t0 - tol && t_out <= t0 + h() + tol))
    throw Error("state_at(" + format(t_out, 17) + "): the time must lie within one step of t = " +
                format(t0, 17) + " (in [t, t + h], h = " + format(h(), 17) + ")");
  q = this->q();
  p = this->p();
  if (is_now(t_out)) return;
  detail::StepperBase& s = stepper_of_size(t_out - t0);
  const long steps = statistics_.steps;
  s.step(steps + 1, t0, statistics_);
  s.get_state(q, p, statistics_);
  statistics_.steps = steps;  // (not a step of the trajectory)
}

void Integrator::require_output_times(double t_end,
                                      const Eigen::Ref<const Eigen::VectorXd>& times) const {
  grid_.require_output_times(t_end, times);
  if (method_.entire()) return;  // (any step size: no shorter step to check)
  for (double tau : times) require_reachable(tau);
}

bool Integrator::reach(double tau) {
  batches(grid_.plan_to(tau).whole);
  if (stale_) load();  // (here rather than in q(): one call per output time less)
  return is_now(tau);
}

// The step of size t_out - t_n from the last grid point t_n before t_out clears the poles (an
// output time's or t_end's shorter step, validated before any step is taken).
void Integrator::require_reachable(double t_out) const {
  const TimeGrid::Plan plan = grid_.plan_to(t_out);
  if (!plan.shorter) return;
  const double size = t_out - grid_.ahead(plan.whole);
  try {
    detail::check_step_size(method_, size, system().M.eigenvalues(), options_.pole_tolerance);
  } catch (const Error& e) {
    throw Error("a step of size " + format(size, 17) + " (to t = " + format(t_out, 17) +
                ", off the grid of h = " + format(h(), 17) + ") is refused: " + e.what());
  }
}

double Integrator::energy() const { return energy(q(), p()); }

double Integrator::energy(const Eigen::VectorXd& q, const Eigen::VectorXd& p) const {
  const System& s = system();
  if (!s.potential) throw Error("energy() needs System::potential");
  if (q.size() != q_.size() || p.size() != q_.size())
    throw Error("energy(q, p): q and p must have size " + std::to_string(q_.size()));
  Eigen::VectorXd Mq(q.size());
  stepper_->apply_M(q, Mq);
  return 0.5 * p.squaredNorm() + 0.5 * q.dot(Mq) + s.potential(q);
}

// The guard's measure at (q, p) (BlowupGuard::measure); `scale` (if given) receives
// 1/2|p|^2 + 1/2 q'M q + |U(q)| (U where the guard needs it, else 0).
double Integrator::guard_measure(const Eigen::VectorXd& q, const Eigen::VectorXd& p,
                                 double* scale) const {
  Eigen::VectorXd& Mq = guard_->workspace(q.size());
  stepper_->apply_M(q, Mq);
  detail::BlowupGuard::Sums sums{0.5 * p.squaredNorm() + 0.5 * q.dot(Mq), 0};
  if (guard_->needs_potential(bool(system().potential))) sums.U = system().potential(q);
  if (scale) *scale = sums.scale();
  return guard_->measure(sums);
}

// The guard's reference: the measure of the state it started at, (q, p).
void Integrator::start_guard(const Eigen::VectorXd& q, const Eigen::VectorXd& p) {
  double scale = 0;
  const double H = guard_measure(q, p, &scale);
  guard_->set_reference(H, scale, bool(system().potential));
}

// The checkpoint of the current state (q_, p_ current at every call): its grid and step count,
// and q_, p_ themselves until they change (keep_checkpoint). (Copying them cost ~7.5 us of a
// construction at N = 8192.) Without the guard nothing returns to it: q_, p_ are not kept, and
// the first load after stepping allocates no vectors for it.
void Integrator::save_checkpoint() {
  time_resolved_ = grid_.resolved();
  detail::BlowupGuard::Checkpoint& c = guard_->checkpoint();
  checkpoint_in_state_ = guard_->on();
  c.grid = grid_, c.steps = statistics_.steps;
}

// The checkpoint's state: q_, p_ while they hold it, else the checkpoint's own vectors.
std::pair<const Eigen::VectorXd&, const Eigen::VectorXd&> Integrator::checkpoint_state() const {
  if (checkpoint_in_state_) return {q_, p_};
  const detail::BlowupGuard::Checkpoint& c = guard_->checkpoint();
  return {c.q, c.p};
}

void Integrator::start_guard_at_checkpoint() {
  const auto [q, p] = checkpoint_state();
  start_guard(q, p);
}

// A check of the guard: passed, the state becomes the checkpoint; failed, the checkpoint becomes
// the state again and the run stops. After a step that failed with `failure`, a passed check
// changes nothing (the caller rethrows the failure).
void Integrator::check_guard(const char* failure) {
  if (guard_->pending()) start_guard_at_checkpoint();
  const double measure = guard_measure(q(), p(), nullptr);
  if (guard_->growth(measure) <= 1) return failure ? void() : save_checkpoint();
  const double t_now = t();
  const long step_now = statistics_.steps;
  const auto [q, p] = checkpoint_state();
  if (&q != &q_) q_ = q, p_ = p;  // (q_, p_ may hold it already)
  stepper_->set_state(q_, p_, statistics_);
  stale_ = false;
  const detail::BlowupGuard::Checkpoint& c = guard_->checkpoint();
  grid_ = c.grid, statistics_.steps = c.steps;
  std::string message = guard_->message(measure, t_now, step_now, t(), likely_cause());
  if (failure) message += ". The next step then failed: " + std::string(failure);
  throw Error(message);
}

// The step-size advisor's verdict at h from the current state (erkn/advisor.hpp).
std::string Integrator::likely_cause() const {
  return detail::BlowupGuard::likely_cause(
      [&] { return advise_step_size(method_, system(), h(), q(), p()); }, method_, h());
}

}  // namespace erkn
