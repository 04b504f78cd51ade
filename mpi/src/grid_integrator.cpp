// GridIntegrator: the step of eq. (d), as erkn::Integrator takes it, on a slab-distributed grid.
// The stages are solved by fixed-point iteration from the previous step's stages extrapolated,
// stopping when theta/(1-theta)|dQ| <= tolerance; its norms are one MPI_Allreduce per iteration,
// which also carries the check that every rank's gradient was finite, so all ranks take every
// decision together.
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <utility>

#include "collective.hpp"
#include "compensated_sum.hpp"  // (runtime/src)
#include "erkn/mpi.hpp"
#include "erkn/time_grid.hpp"
#include "slab_transform.hpp"
#include "step_coefficients.hpp"  // (runtime/src)
#include "step_size_check.hpp"    // (runtime/src)

namespace erkn::mpi {
namespace detail {

using erkn::detail::StepCoefficients;

/// A duplicate of the user's communicator (our collectives never meet the user's messages),
/// freed last, after the transforms planned on it.
struct Communicator {
  explicit Communicator(MPI_Comm comm) { MPI_Comm_dup(comm, &handle); }
  ~Communicator() { MPI_Comm_free(&handle); }
  Communicator(const Communicator&) = delete;
  Communicator& operator=(const Communicator&) = delete;
  MPI_Comm handle;
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
        rkn_(method.kind() == Kind::rkn),
        s_(method.stages()),
        T_(comm_, system_.M),
        // (RKN methods: V = 0, their force includes M Q)
        lambda_(rkn_ ? Eigen::VectorXd::Zero(T_.spectral_size()).eval()
                     : Eigen::VectorXd(T_.eigenvalues().matrix())),
        k_h_(method, h, lambda_) {
    slab_ = {T_.first_row(), T_.rows(), T_.physical_size()};
    q_ = q0, p_ = p0;
    q_error_.setZero(slab_.size), p_error_.setZero(slab_.size);
    const Eigen::Index m = T_.spectral_size();
    for (Eigen::ArrayXd* a :
         {&q_hat_, &p_hat_, &r_hat_, &Q_hat_, &Q_new_hat_, &guess_hat_, &dq_hat_, &dp_hat_})
      a->setZero(m);
    G_.assign(std::size_t(s_), Eigen::ArrayXd::Zero(m));
    G_old_ = G_;
    for (Eigen::VectorXd* x : {&Q_, &g_, &dq_, &dp_}) x->setZero(slab_.size);
    const double* c = method.table().c;  // Lagrange weights from c_j to 1 + c_i, as Stepper
    for (int i = 0; i < s_; ++i)
      for (int j = 0; j < s_; ++j) {
        double w = 1;
        for (int l = 0; l < s_; ++l)
          if (l != j) w *= (1 + c[i] - c[l]) / (c[j] - c[l]);
        extrapolation_[i][j] = w;
      }
  }

  /// One step of size h, or with short_step = true of the size given to prepare_short (the
  /// caller then restarts the time grid at its end; the stage history is not used across it).
  void step(bool short_step = false) {
    k_ = short_step ? &*k_short_ : &k_h_;
    if (short_step) have_history_ = false;
    T_.forward(q_, q_hat_);
    T_.forward(p_, p_hat_);
    for (int i = 0; i < s_; ++i) {
      start_stage(i);
      fixed_point(i);
    }
    dq_hat_ = k_->phi0m1() * q_hat_ + k_->hphi1() * p_hat_;
    dp_hat_ = k_->mhMphi1() * q_hat_ + k_->phi0m1() * p_hat_;
    for (int i = 0; i < s_; ++i) {
      dq_hat_ -= k_->h2bbar(i) * G_[i];
      dp_hat_ -= k_->hb(i) * G_[i];
    }
    T_.inverse(dq_hat_, dq_);
    T_.inverse(dp_hat_, dp_);
    add(q_, q_error_, dq_);
    add(p_, p_error_, dp_);
    std::swap(G_, G_old_);
    have_history_ = !short_step;
    ++statistics_.steps;
    grid_.advance();
  }

  /// The coefficients of a shorter step (checked against the poles; the same on every rank).
  void prepare_short(double h_short) {
    if (k_short_ && short_h_ == h_short) return;
    erkn::detail::check_step_size(method_, h_short, system_.M.eigenvalues(),
                                  options_.pole_tolerance);
    k_short_.emplace(method_, h_short, lambda_);
    short_h_ = h_short;
  }

  double energy() {
    if (!system_.potential) throw Error("energy() needs System::potential");
    T_.forward(q_, q_hat_);
    double local =
        0.5 * p_.squaredNorm() + 0.5 * (T_.weights() * T_.eigenvalues() * q_hat_.square()).sum();
    collectively(comm_, [&] { local += system_.potential(q_); });
    MPI_Allreduce(MPI_IN_PLACE, &local, 1, MPI_DOUBLE, MPI_SUM, comm_);
    return local;
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
  bool rkn_;
  int s_;
  detail::SlabTransform T_;
  Eigen::VectorXd lambda_;  // where the coefficients are evaluated
  StepCoefficients<Eigen::ArrayXd> k_h_;
  std::optional<StepCoefficients<Eigen::ArrayXd>> k_short_;  // of the last shorter step
  double short_h_ = 0;
  const StepCoefficients<Eigen::ArrayXd>* k_ = &k_h_;  // of the step being taken
  Slab slab_;
  Statistics statistics_;
  Eigen::VectorXd q_, p_, q_error_, p_error_;

 private:
  void start_stage(int i) {
    r_hat_ = k_->phi0c(i) * q_hat_ + k_->hcphi1c(i) * p_hat_;
    for (int j = 0; j < i; ++j) r_hat_ -= k_->abar(i, j) * G_[j];
    if (have_history_) {
      guess_hat_ = extrapolation_[i][0] * G_old_[0];
      for (int j = 1; j < s_; ++j) guess_hat_ += extrapolation_[i][j] * G_old_[j];
    } else if (i > 0) {
      guess_hat_ = G_[i - 1];
    } else {
      guess_hat_.setZero();
    }
    Q_hat_ = r_hat_ - k_->abar(i, i) * guess_hat_;
  }

  // Q <- r_i - h^2 abar_ii(V) g(Q) until theta/(1-theta)|dQ| <= tolerance (Stepper::fixed_point;
  // the same decisions, from norms summed over the ranks).
  void fixed_point(int i) {
    double delta = 0, delta_old = 0, norm_Q = 0;
    for (int it = 1; it <= options_.max_fixed_point_iterations; ++it) {
      T_.inverse(Q_hat_, Q_);
      const double bad = gradient();
      T_.forward(g_, G_[i]);
      if (rkn_) G_[i] += T_.eigenvalues() * Q_hat_;  // the RKN force includes M Q
      Q_new_hat_ = r_hat_ - k_->abar(i, i) * G_[i];
      ++statistics_.stage_iterations;
      // One allreduce: |dQ|^2, |Q_new|^2, |Q|^2 (first iteration) and the gradient check.
      std::array<double, 4> sums{T_.local_squared_norm(Q_new_hat_ - Q_hat_),
                                 T_.local_squared_norm(Q_new_hat_),
                                 it == 1 ? T_.local_squared_norm(Q_hat_) : 0.0, bad};
      MPI_Allreduce(MPI_IN_PLACE, sums.data(), 4, MPI_DOUBLE, MPI_SUM, comm_);
      if (sums[3] > 0) gradient_failed(i);
      const double change = std::sqrt(sums[0]), norm_new = std::sqrt(sums[1]);
      if (it == 1) norm_Q = std::sqrt(sums[2]);
      const double scale = std::max({norm_new, norm_Q, 1e-300});
      delta = change == 0 ? 0.0 : change / scale;
      norm_Q = norm_new;
      Q_hat_.swap(Q_new_hat_);
      if (delta == 0) return;
      if (it > 1) {
        const double theta = delta / delta_old;
        if (theta < 1 && theta / (1 - theta) * delta <= options_.tolerance) return;
        if (theta >= options_.max_theta) {
          if (delta <= options_.roundoff_level) return;
          not_converged(i, delta);
        }
        const double needed =
            std::log(options_.tolerance * (1 - theta) / (theta * delta)) / std::log(theta);
        if (it + needed > options_.max_fixed_point_iterations && delta > options_.roundoff_level)
          not_converged(i, delta);
      }
      delta_old = delta;
    }
    if (delta > options_.roundoff_level) not_converged(i, delta);
  }

  // g_ = grad U(Q_) on this slab; returns 1 if it is not finite or has the wrong size (then g_
  // is zeroed so the transform stays defined), else 0.
  // (A callback that throws on one rank must not leave the others in the next collective call:
  // its exception becomes this rank's error, reported on every rank by gradient_failed.)
  double gradient() {
    ++statistics_.gradient_evaluations;
    try {
      system_.gradient(Q_, g_);
      if (g_.size() == slab_.size && g_.allFinite()) return 0;
      local_gradient_error_ = g_.size() != slab_.size
                                  ? "the gradient callback returned a vector of size " +
                                        std::to_string(g_.size()) + " for a slab of size " +
                                        std::to_string(slab_.size)
                                  : "the gradient callback returned a non-finite value";
    } catch (const std::exception& e) {
      local_gradient_error_ = std::string("the gradient callback threw: ") + e.what();
    } catch (...) {
      local_gradient_error_ = "the gradient callback threw an exception of unknown type";
    }
    g_.setZero(slab_.size);
    return 1;
  }

  [[noreturn]] void gradient_failed(int i) {
    const std::string where = " at step " + std::to_string(statistics_.steps + 1) + ", stage " +
                              std::to_string(i + 1) + "; the state is unchanged";
    std::string mine = local_gradient_error_.empty() ? "" : local_gradient_error_ + where;
    local_gradient_error_.clear();
    throw_if_any(comm_, mine);
    throw Error("internal: gradient check disagreement");  // (unreachable: some rank failed)
  }

  [[noreturn]] void not_converged(int i, double delta) {
    throw Error("step " + std::to_string(statistics_.steps + 1) + ": stage " +
                std::to_string(i + 1) + " of " + std::string(method_.name()) +
                " did not converge by fixed-point iteration (last relative change " +
                std::to_string(delta) +
                "); the distributed integrator has no Newton fallback: reduce h. The state is "
                "unchanged");
  }

  // x += dx, Kahan-compensated when enabled (the library's update, compensated_sum.hpp).
  void add(Eigen::VectorXd& x, Eigen::VectorXd& error, Eigen::VectorXd& dx) {
    if (options_.compensated_summation)
      erkn::detail::compensated_add(x, error, dx);
    else
      x += dx;
  }

  std::array<std::array<double, kMaxStages>, kMaxStages> extrapolation_{};
  bool have_history_ = false;
  std::string local_gradient_error_;
  Eigen::ArrayXd q_hat_, p_hat_, r_hat_, Q_hat_, Q_new_hat_, guess_hat_, dq_hat_, dp_hat_;
  std::vector<Eigen::ArrayXd> G_, G_old_;  // this and the previous step's stage gradients
  Eigen::VectorXd Q_, g_, dq_, dp_;
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
  const detail::SlabLayout l = detail::slab_layout(comm, M);
  return {l.first0, l.rows0, l.physical_size};
}

GridIntegrator::GridIntegrator(MPI_Comm comm, const Method& method, System system, double h,
                               const Eigen::VectorXd& q0, const Eigen::VectorXd& p0,
                               const Options& options) {
  // The same checks on every rank; the size check differs per rank, so it is made collective.
  detail::collectively(comm, [&] {
    if (system.M.structure() != Stiffness::Structure::grid)
      throw Error("the distributed integrator needs M = Stiffness::grid");
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
  // A failed step leaves q, p unchanged (they are only written at its end).
  stepper_->step();
}

void GridIntegrator::integrate(double t_end) {
  // Integrator's time grid (erkn/time_grid.hpp): whole steps of h to the last grid point t_n
  // before t_end (a time within round-off of a grid point is that point), then one shorter step
  // t_end - t_n. (The same decisions on every rank: every rank has the same times.)
  detail::GridStepper& s = *stepper_;
  const TimeGrid::Plan plan = s.grid_.plan_to(t_end);
  if (plan.shorter)
    detail::collectively(s.comm_, [&] { s.prepare_short(t_end - s.grid_.ahead(plan.whole)); });
  for (long k = 0; k < plan.whole; ++k) s.step();
  if (plan.shorter) {
    s.step(true);
    s.grid_.restart(t_end);  // (t() == t_end exactly)
  }
}

const Eigen::VectorXd& GridIntegrator::q() const { return stepper_->q_; }
const Eigen::VectorXd& GridIntegrator::p() const { return stepper_->p_; }
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
