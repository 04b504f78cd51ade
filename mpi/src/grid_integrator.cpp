// GridIntegrator: the step of eq. (d), as erkn::Integrator takes it, on a slab-distributed grid:
// the library's stage solver (runtime/src/stage_solver.hpp: predictor, fixed point with the
// first-iteration stop, Newton-Krylov fallback) over the slab space (slab_space.hpp), whose
// reduce is one MPI_Allreduce that also carries the check that every rank's gradient was good, so
// all ranks take every decision together. An explicit method (every abar_ii = 0) steps as
// erkn::Integrator steps it: the library's ExplicitStepper (runtime/src/explicit_stepper.hpp:
// passes of flows and kicks, O(s) arrays per step, FSAL) over the same slab space, whose checks
// are one reduce at the end of each step. Between the steps of one call the state stays in M's
// eigenbasis (with the compensated sums' errors there), as erkn::Integrator keeps it: a step
// transforms only its stages, and the physical state is loaded (two inverse transforms) when a
// call returns, before a check of the blow-up guard and for energy(), so q() and p() are this
// rank's slab without a collective call. The blow-up guard is erkn::Integrator's
// (runtime/src/blowup_guard.hpp), its sums reduced by the same reduce.
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <utility>

#include "blowup_guard.hpp"  // (runtime/src)
#include "collective.hpp"
#include "distributed_transform.hpp"
#include "erkn/mpi.hpp"
#include "erkn/time_grid.hpp"
#include "explicit_stepper.hpp"  // (runtime/src)
#include "implicit_passes.hpp"   // (runtime/src)
#include "slab_advice.hpp"
#include "slab_space.hpp"
#include "stage_solver.hpp"       // (runtime/src)
#include "step_coefficients.hpp"  // (runtime/src)
#include "step_size_check.hpp"    // (runtime/src)

namespace erkn::mpi {
namespace detail {

using erkn::detail::BlowupGuard;
using erkn::detail::StepCoefficients;
using Solver = erkn::detail::StageSolver<SlabSpace, Eigen::ArrayXd>;
using erkn::detail::StepperBase;
using ExplicitSlabStepper = erkn::detail::ExplicitStepper<SlabSpace, Eigen::ArrayXd>;

/// A duplicate of the user's communicator (our collectives never meet the user's messages),
/// freed last, after the transforms planned on it.
struct Communicator {
  explicit Communicator(MPI_Comm comm) { MPI_Comm_dup(comm, &handle); }
  ~Communicator() { MPI_Comm_free(&handle); }
  Communicator(const Communicator&) = delete;
  Communicator& operator=(const Communicator&) = delete;
  MPI_Comm handle;
};

/// The coefficients of one step size and the stage solver over them (implicit methods).
struct Stages {
  Stages(const Method& method, const System& system, const Options& options, SlabSpace& space,
         double h, const Eigen::VectorXd& lambda)
      : k(method, h, lambda), solver(method, system, options, space, k) {}
  StepCoefficients<Eigen::ArrayXd> k;
  Solver solver;
};

/// This rank's slab of the state: in eigen coordinates (q_hat, p_hat and their compensated
/// sums' errors; an explicit method's: in its stepper) while stepping, physical (q, p) when
/// loaded; and a step's increments.
struct SlabState {
  explicit SlabState(Eigen::Index m) {
    for (Eigen::ArrayXd* a : {&q_hat, &p_hat, &q_error, &p_error, &dq_hat, &dp_hat}) a->setZero(m);
  }
  Eigen::VectorXd q, p;
  Eigen::ArrayXd q_hat, p_hat, q_error, p_error, dq_hat, dp_hat;
  bool physical = true, spectral = false;  // which of the two is the current state
};

class GridStepper {
 public:
  GridStepper(MPI_Comm comm, const Method& method, System system, double h,
              const Eigen::VectorXd& q0, const Eigen::VectorXd& p0, const Options& options)
      : communicator_(comm),
        comm_(communicator_.handle),
        method_(method),
        system_(std::move(system)),
        options_(options),
        grid_(0, h),
        transform_(distributed_transform(comm_, system_.M)),
        T_(*transform_),
        space_(comm_, T_, method.kind() == Kind::rkn),
        // (RKN methods: V = 0, their force includes M Q)
        lambda_(method.kind() == Kind::rkn ? Eigen::VectorXd::Zero(T_.spectral_size()).eval()
                                           : Eigen::VectorXd(T_.eigenvalues().matrix())),
        x_(T_.spectral_size()) {
    if (explicit_method())
      explicit_ = explicit_stepper(h);
    else
      stages_.emplace(method_, system_, options_, space_, h, lambda_);
    slab_ = {T_.first_row(), T_.rows(), T_.physical_size()};
    x_.q = q0, x_.p = p0;
    guard_.start(options_.blowup_guard);  // (its reference, at the checkpoint: when first needed)
    save_checkpoint();
  }

  /// step() under the blow-up guard (Options::blowup_guard); a shorter step ends at *t_end,
  /// where the time grid restarts (t() == t_end exactly).
  void guarded_step(std::optional<double> t_end = {}) {
    try {
      step(t_end.has_value());
    } catch (const Error& e) {  // (a blow-up often ends in a failed stage: say so)
      if (guard_.on()) check_guard(e.what());
      throw;
    }
    if (t_end) grid_.restart(*t_end);
    if (guard_.due()) check_guard();
  }

  /// One step of size h, or with short_step = true of the size given to prepare_short (the
  /// caller then restarts the time grid at its end; the stage history is not used across it).
  void step(bool short_step = false) {
    Statistics counts;  // (added once the step has succeeded)
    if (explicit_)
      explicit_step(short_step, counts);
    else
      implicit_step(short_step, counts);
    statistics_.gradient_evaluations += counts.gradient_evaluations;
    statistics_.stage_iterations += counts.stage_iterations;
    statistics_.newton_fallbacks += counts.newton_fallbacks;
    statistics_.newton_iterations += counts.newton_iterations;
    ++statistics_.steps;
    grid_.advance();
  }

  /// The coefficients of a shorter step (checked against the poles; the same on every rank).
  void prepare_short(double h_short) {
    if (h_short_ == h_short) return;
    erkn::detail::check_step_size(method_, h_short, system_.M.eigenvalues(),
                                  options_.pole_tolerance);
    if (explicit_)
      explicit_short_ = explicit_stepper(h_short);
    else
      short_.emplace(method_, system_, options_, space_, h_short, lambda_);
    h_short_ = h_short;
  }

  double energy() {
    if (!system_.potential) throw Error("energy() needs System::potential");
    load();
    return sums(x_.q, x_.p, true).H();
  }

  /// steps(), then the physical state loaded, also when steps() throws (its errors are thrown
  /// on every rank alike): the state of the last step that succeeded.
  template <class Steps>
  void loaded(Steps&& steps) {
    try {
      steps();
    } catch (...) {
      load();
      throw;
    }
    load();
  }

  /// The physical state from the eigen coordinates, if it is not current (collective).
  void load() {
    if (x_.physical) return;
    if (explicit_) {
      Statistics none;  // (an unprocessed method's get_state counts nothing)
      explicit_->get_state(x_.q, x_.p, none);
    } else {
      x_.dq_hat = x_.q_hat + x_.q_error;  // (the increments' storage is free between steps)
      x_.dp_hat = x_.p_hat + x_.p_error;
      space_.inverse(x_.dq_hat, x_.q);
      space_.inverse(x_.dp_hat, x_.p);
    }
    x_.physical = true;
  }

  Eigen::VectorXd gather(const Eigen::VectorXd& local) const {
    const std::vector<double> all = all_gather(comm_, local.data(), int(local.size()), MPI_DOUBLE);
    return Eigen::Map<const Eigen::VectorXd>(all.data(), Eigen::Index(all.size()));
  }

  Communicator communicator_;
  MPI_Comm comm_;
  Method method_;
  System system_;
  Options options_;
  TimeGrid grid_;  // (validates h)
  std::unique_ptr<DistributedTransform> transform_;
  DistributedTransform& T_;
  SlabSpace space_;
  Eigen::VectorXd lambda_;                // where the coefficients are evaluated
  std::optional<Stages> stages_, short_;  // (implicit methods) of h, of the last shorter step
  std::unique_ptr<StepperBase> explicit_, explicit_short_;  // (explicit methods) the same
  double h_short_ = 0;                                      // (0: no shorter step prepared)
  Slab slab_;
  Statistics statistics_;
  SlabState x_;
  BlowupGuard guard_;

 private:
  // E_2 = 1/2|p|^2 + 1/2 q'M q (q'M q by Parseval in eigen coordinates) and, with_U, U(q) over
  // every rank (the slabs' parts summed by the space's reduce). x_.dq_hat is free between steps.
  BlowupGuard::Sums sums(const Eigen::VectorXd& q, const Eigen::VectorXd& p, bool with_U) {
    T_.forward(q, x_.dq_hat);
    std::array<double, 2> local{
        0.5 * p.squaredNorm() + 0.5 * (T_.weights() * T_.eigenvalues() * x_.dq_hat.square()).sum(),
        0.0};
    if (with_U) collectively(comm_, [&] { local[1] = system_.potential(q); });
    const std::array<double, 2> all = space_.reduce(local);
    return {all[0], all[1]};
  }

  // A check of the guard (collective, and every rank decides alike: the sums are reduced):
  // passed, the state becomes the checkpoint; failed, the checkpoint becomes the state again and
  // the run stops. After a step that failed with `failure`, a passed check changes nothing (the
  // caller rethrows the failure).
  void check_guard(const char* failure = nullptr) {
    load();  // (a failed step changed nothing: the state before it)
    const bool potential = bool(system_.potential);
    if (guard_.pending()) {
      const BlowupGuard::Checkpoint& c = guard_.checkpoint();
      const BlowupGuard::Sums start = sums(c.q, c.p, guard_.needs_potential(potential));
      guard_.set_reference(start.H(), start.scale(), potential);
    }
    const double measure = guard_.measure(sums(x_.q, x_.p, guard_.needs_potential(potential)));
    if (guard_.growth(measure) <= 1) return failure ? void() : save_checkpoint();
    const double t_now = grid_.t();
    const long step_now = statistics_.steps;
    restore_checkpoint();
    std::string message = guard_.message(measure, t_now, step_now, grid_.t(), likely_cause());
    if (failure) message += ". The next step then failed: " + std::string(failure);
    throw Error(message);
  }

  void save_checkpoint() {
    BlowupGuard::Checkpoint& c = guard_.checkpoint();
    c.q = x_.q, c.p = x_.p;
    c.grid = grid_, c.steps = statistics_.steps;
  }

  void restore_checkpoint() {
    const BlowupGuard::Checkpoint& c = guard_.checkpoint();
    x_.q = c.q, x_.p = c.p;
    x_.physical = true, x_.spectral = false;
    grid_ = c.grid, statistics_.steps = c.steps;
    if (stages_) stages_->solver.reset();  // (its history is of the steps after the checkpoint)
  }

  bool explicit_method() const { return erkn::detail::explicit_stages(method_); }

  // The library's explicit stepper of step size h over this rank's slab (RKN methods: flows of
  // lambda = 0, the force with M Q added in eigen coordinates by the space).
  std::unique_ptr<StepperBase> explicit_stepper(double h) const {
    return std::make_unique<ExplicitSlabStepper>(method_, System(system_), h, options_,
                                                 SlabSpace(comm_, T_, method_.kind() == Kind::rkn),
                                                 lambda_, T_.physical_size());
  }

  // A step of the stage solver from the state in eigen coordinates (transformed first after
  // construction or a restored checkpoint), eq. (d)'s update added.
  void implicit_step(bool short_step, Statistics& counts) {
    Stages& st = short_step ? *short_ : *stages_;
    if (short_step) st.solver.reset();
    if (!x_.spectral) {
      space_.forward(x_.q, x_.q_hat);
      space_.forward(x_.p, x_.p_hat);
      x_.q_error.setZero(), x_.p_error.setZero();
      x_.spectral = true;
    }
    st.solver.count(
        st.solver.solve(x_.q_hat, x_.p_hat, {&method_, statistics_.steps + 1, grid_.t()}), counts);
    update(st);
    st.solver.advance();
    if (short_step) stages_->solver.reset();  // (its history is of the grid before)
  }

  // A step of the explicit stepper, which holds the state between steps (set after construction
  // or a restored checkpoint). A shorter step, as Integrator::step_to takes it: the physical
  // state into the shorter step's stepper, stepped, and back (h's stepper starts from it again).
  void explicit_step(bool short_step, Statistics& counts) {
    StepperBase& s = short_step ? *explicit_short_ : *explicit_;
    if (short_step) load(), x_.spectral = false;
    if (!x_.spectral) s.set_state(x_.q, x_.p, counts), x_.spectral = true;
    s.step(statistics_.steps + 1, grid_.t(), counts);
    x_.physical = false;
    if (!short_step) return;
    s.get_state(x_.q, x_.p, counts);
    x_.physical = true, x_.spectral = false;
  }

  // The step-size advisor's verdict at h at the (kept) state: its linear model (slab_advice.hpp).
  std::string likely_cause() {
    return BlowupGuard::likely_cause(
        [&] { return slab_advice(comm_, T_, method_, system_, grid_.h(), x_.q, x_.p); }, method_,
        grid_.h());
  }

  // Eq. (d)'s update from the solved stages, added to the state (eigen coordinates) at the end:
  // the serial stepper's passes (implicit_passes.hpp, one coordinate per double). (The result's
  // finiteness is the blow-up guard's, as before: the passes' non-finite bits are not used.)
  void update(Stages& st) {
    using erkn::detail::add_pass;
    const StepCoefficients<Eigen::ArrayXd>& k = st.k;
    const erkn::detail::UpdateCoefficients<const double*> c{k.phi0m1().data(), k.hphi1().data(),
                                                            k.mhMphi1().data()};
    const Eigen::Index n = x_.q_hat.size();
    erkn::detail::update_passes<1>(
        method_.stages(), n, x_.q_hat.data(), x_.p_hat.data(), x_.dq_hat.data(), x_.dp_hat.data(),
        c, [&](int i) {
          return std::tuple{st.solver.G(i).data(), k.h2bbar(i).data(), k.hb(i).data()};
        });
    for (auto [x, error, dx] : {std::tuple{&x_.q_hat, &x_.q_error, &x_.dq_hat},
                                std::tuple{&x_.p_hat, &x_.p_error, &x_.dp_hat}}) {
      if (options_.compensated_summation)
        add_pass<1, true>(n, x->data(), error->data(), dx->data());
      else
        add_pass<1, false>(n, x->data(), error->data(), dx->data());
    }
    x_.physical = false;
  }
};

}  // namespace detail

namespace {

std::string check_input(const System& system, const Eigen::VectorXd& q0, const Eigen::VectorXd& p0,
                        Eigen::Index expected) {
  if (!system.gradient) return "System::gradient is not set";
  if (q0.size() != expected || p0.size() != expected)
    return "this rank's slab has " + std::to_string(expected) + " unknowns; q0 has " +
           std::to_string(q0.size()) + ", p0 " + std::to_string(p0.size());
  if (!q0.allFinite() || !p0.allFinite()) return "q0 or p0 is not finite";
  return "";
}

}  // namespace

Slab slab(MPI_Comm comm, const Stiffness& M) {
  const detail::LocalPart part = detail::local_part(comm, M);
  return {part.first, part.rows, part.size};
}

GridIntegrator::GridIntegrator(MPI_Comm comm, const Method& method, System system, double h,
                               const Eigen::VectorXd& q0, const Eigen::VectorXd& p0,
                               const Options& options) {
  // The same checks on every rank; the size check differs per rank, so it is made collective.
  detail::collectively(comm, [&] {
    if (system.M.structure() != Stiffness::Structure::grid &&
        system.M.structure() != Stiffness::Structure::circulant)
      throw Error("the distributed integrator needs M = Stiffness::grid or Stiffness::circulant");
    if (method.has_modified_kicks())
      throw Error(std::string(method.name()) +
                  " has modified kicks (grad(|grad U|^2)), which the distributed integrator "
                  "does not form: use a method with plain kicks (Method::has_modified_kicks() "
                  "false), or erkn::Integrator on one process");
    if (method.is_processed())
      throw Error(std::string(method.name()) +
                  " is processed (psi = pi o K o pi^-1), and the distributed integrator has no "
                  "processor: use an unprocessed method (Method::is_processed() false), or "
                  "erkn::Integrator on one process");
    const TimeGrid grid(0, h);  // (validates h, the same on every rank)
    erkn::detail::check_step_size(method, h, system.M.eigenvalues(), options.pole_tolerance);
  });
  std::unique_ptr<detail::GridStepper> stepper;
  detail::collectively(comm, [&] {
    stepper = std::make_unique<detail::GridStepper>(comm, method, system, h, q0, p0, options);
  });
  detail::throw_if_any(comm, check_input(system, q0, p0, stepper->slab_.size));
  stepper_ = std::move(stepper);
}

GridIntegrator::~GridIntegrator() = default;
GridIntegrator::GridIntegrator(GridIntegrator&&) noexcept = default;
GridIntegrator& GridIntegrator::operator=(GridIntegrator&&) noexcept = default;

void GridIntegrator::step() {
  // A failed step leaves q, p unchanged (they are only written at its end); a failed check of the
  // blow-up guard restores the state of the last check that passed.
  detail::GridStepper& s = *stepper_;
  s.loaded([&] { s.guarded_step(); });
}

void GridIntegrator::integrate(double t_end) {
  // Integrator's time grid (erkn/time_grid.hpp): whole steps of h to the last grid point t_n
  // before t_end (a time within round-off of a grid point is that point), then one shorter step
  // t_end - t_n. (The same decisions on every rank: every rank has the same times.)
  detail::GridStepper& s = *stepper_;
  const TimeGrid::Plan plan = s.grid_.plan_to(t_end);
  if (plan.shorter)
    detail::collectively(s.comm_, [&] { s.prepare_short(t_end - s.grid_.ahead(plan.whole)); });
  s.loaded([&] {
    for (long k = 0; k < plan.whole; ++k) s.guarded_step();
    if (plan.shorter) s.guarded_step(t_end);
  });
}

const Eigen::VectorXd& GridIntegrator::q() const { return stepper_->x_.q; }
const Eigen::VectorXd& GridIntegrator::p() const { return stepper_->x_.p; }
double GridIntegrator::t() const { return stepper_->grid_.t(); }
double GridIntegrator::h() const { return stepper_->grid_.h(); }
const Slab& GridIntegrator::slab() const { return stepper_->slab_; }
const Statistics& GridIntegrator::statistics() const { return stepper_->statistics_; }
long GridIntegrator::transforms() const { return stepper_->T_.count(); }
double GridIntegrator::transform_seconds() const { return stepper_->T_.seconds(); }
double GridIntegrator::energy() { return stepper_->energy(); }
Eigen::VectorXd GridIntegrator::gather(const Eigen::VectorXd& local) const {
  return stepper_->gather(local);
}

}  // namespace erkn::mpi
