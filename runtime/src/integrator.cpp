#include "erkn/integrator.hpp"

#include <cmath>
#include <string>

#include "erkn/error.hpp"
#include "format.hpp"
#include "step_size_check.hpp"
#include "stepper.hpp"
#include "transforms.hpp"

namespace erkn {
namespace {

void require_step_size(double h) {
  if (!std::isfinite(h) || h <= 0)
    throw Error("the step size h must be finite and > 0; got h = " + format(h));
}

void require_state(const System& system, const Eigen::VectorXd& q, const Eigen::VectorXd& p) {
  if (q.size() == 0) throw Error("q is empty");
  if (p.size() != q.size())
    throw Error("dimension mismatch: q has size " + std::to_string(q.size()) + ", p has size " +
                std::to_string(p.size()));
  if (system.M.dim() != 0 && system.M.dim() != q.size())
    throw Error("dimension mismatch: M is " + std::to_string(system.M.dim()) + "x" +
                std::to_string(system.M.dim()) + ", q has size " + std::to_string(q.size()));
  for (Eigen::Index i = 0; i < q.size(); ++i) {
    if (!std::isfinite(q[i]))
      throw Error("q[" + std::to_string(i) + "] = " + format(q[i]) + " is not finite");
    if (!std::isfinite(p[i]))
      throw Error("p[" + std::to_string(i) + "] = " + format(p[i]) + " is not finite");
  }
}

// Circulant M up to this N uses the explicit Fourier basis (folded matrix-vector products,
// O(N^2)), beyond it the FFT (O(N log N)). Measured with erkn_step_benchmark, BM_StepCirculant
// (SERKN3s4(1), time per step, basis vs FFT): N = 32 5.9 vs 6.1 us, N = 64 12.5 vs 13.3 us,
// N = 128 35 vs 24 us, N = 256 113 vs 55 us.
constexpr Eigen::Index kFourierBasisMaxN = 64;

std::unique_ptr<detail::StepperBase> make_stepper(const Method& method, System system, double h,
                                                  const Options& options, Eigen::Index d) {
  using namespace detail;
  check_step_size(method, h, system.M.eigenvalues(), options.pole_tolerance);
  const Stiffness M = system.M;  // (system is moved into the stepper)
  const Eigen::VectorXd& lambda = M.eigenvalues();
  if (method.kind() == Kind::rkn)
    return std::make_unique<Stepper<IdentityTransform, double>>(
        method, std::move(system), h, options, IdentityTransform{}, Eigen::VectorXd::Zero(1), d);
  switch (M.structure()) {
    case Stiffness::Structure::scalar:
      return std::make_unique<Stepper<IdentityTransform, double>>(
          method, std::move(system), h, options, IdentityTransform{}, lambda, d);
    case Stiffness::Structure::diagonal:
      return std::make_unique<Stepper<IdentityTransform, Eigen::ArrayXd>>(
          method, std::move(system), h, options, IdentityTransform{}, lambda, d);
    case Stiffness::Structure::dense:
      return std::make_unique<Stepper<OrthogonalTransform, Eigen::ArrayXd>>(
          method, std::move(system), h, options, OrthogonalTransform{&M.eigenvectors()}, lambda, d);
    case Stiffness::Structure::circulant:
      if (d <= kFourierBasisMaxN)
        return std::make_unique<Stepper<FourierBasisTransform, Eigen::ArrayXd>>(
            method, std::move(system), h, options, FourierBasisTransform(d),
            FourierBasisTransform::coordinate_eigenvalues(lambda, d), d);
      if (grid_backend_is_fftw())
        return std::make_unique<Stepper<GridTransform, Eigen::ArrayXd>>(
            method, std::move(system), h, options,
            GridTransform({{d, 1.0, GridAxis::Boundary::periodic}}),
            GridTransform::halfcomplex_eigenvalues(lambda, d), d);
      return std::make_unique<Stepper<RealFftTransform, Eigen::ArrayXd>>(
          method, std::move(system), h, options, RealFftTransform(d), lambda, d);
    case Stiffness::Structure::grid:
      return std::make_unique<Stepper<GridTransform, Eigen::ArrayXd>>(
          method, std::move(system), h, options, GridTransform(M.axes()), lambda, d);
  }
  throw Error("unknown structure of M");
}

}  // namespace

Integrator::Integrator(const Method& method, System system, double h, const Eigen::VectorXd& q0,
                       const Eigen::VectorXd& p0, const Options& options)
    : method_(method), options_(options), h_(h) {
  require_step_size(h);
  require_state(system, q0, p0);
  if (!system.gradient) throw Error("System::gradient is not set");
  stepper_ = make_stepper(method, std::move(system), h, options, q0.size());
  q_ = q0;
  p_ = p0;
  q_error_.setZero(q0.size());
  p_error_.setZero(q0.size());
}

Integrator::~Integrator() = default;
Integrator::Integrator(Integrator&&) noexcept = default;
Integrator& Integrator::operator=(Integrator&&) noexcept = default;

const System& Integrator::system() const { return stepper_->system(); }

void Integrator::step() {
  stepper_->step({q_, p_, q_error_, p_error_, statistics_.steps + 1, t()}, statistics_);
  ++steps_since_base_;
}

void Integrator::set_state(const Eigen::VectorXd& q, const Eigen::VectorXd& p, double t) {
  require_state(system(), q, p);
  if (!std::isfinite(t)) throw Error("t = " + format(t) + " is not finite");
  q_ = q;
  p_ = p;
  q_error_.setZero();
  p_error_.setZero();
  t_base_ = t;
  steps_since_base_ = 0;
  stepper_->forget_history();
}

void Integrator::set_step_size(double h) {
  require_step_size(h);
  auto fresh = make_stepper(method_, system(), h, options_, q_.size());
  t_base_ = t();
  steps_since_base_ = 0;
  h_ = h;
  stepper_ = std::move(fresh);
}

long Integrator::steps_until(double t_end) const {
  const double span = t_end - t();
  if (!std::isfinite(span) || span < 0)
    throw Error("t_end = " + format(t_end) + " is not finite or lies before t = " + format(t()));
  const double n = std::round(span / h_);
  if (std::abs(n * h_ - span) > 1e-9 * std::max(h_, std::abs(t_end)))
    throw Error("t_end - t = " + format(span, 17) +
                " is not a whole number of steps h = " + format(h_, 17) + " (" + format(n, 17) +
                " steps reach t = " + format(t() + n * h_, 17) + ")");
  return long(n);
}

double Integrator::energy() const {
  const System& s = system();
  if (!s.potential) throw Error("energy() needs System::potential");
  Eigen::VectorXd Mq(q_.size());
  stepper_->apply_M(q_, Mq);
  return 0.5 * p_.squaredNorm() + 0.5 * q_.dot(Mq) + s.potential(q_);
}

}  // namespace erkn
