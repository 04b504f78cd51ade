// erkn::make_integrator: an Integrator whose explicit steps call a gradient compiled into them.
//
// System::gradient is a std::function on Eigen::VectorXd: an opaque call per stage, across which
// every double of the step is spilled and reloaded (on x86-64 all vector registers are
// caller-saved). For the small systems where that call dominates (d <= 4 with M's identity
// eigenbasis: scalar or diagonal M, or an RKN method) make_integrator instantiates the runtime's
// explicit stepper for d = 1..4 in the calling translation unit with the functor's type known
// (as Boost.odeint's templated systems or Eigen's header-only templates): the functor is inlined
// into the step on fixed-size vectors. With circulant M or a periodic grid (FFTW's half spectrum)
// it instantiates the explicit stepper of that basis with the functor inlined into its gradient
// loop, as a specialist's loop has it (measured: a pointwise gradient such as sine-Gordon's
// through the std::function costs 5-10 % more at N = 32, the specialist's loop through it too).
// Everything else is the Integrator's: the same step (one template, explicit_stepper.hpp),
// checks, messages, statistics, observers and output times, and bit-identical results for the
// same arithmetic. Other dimensions, bases and implicit methods use System::gradient, which
// make_integrator sets to call the same functor.
//
//   #include <cstdio>
//   #include <erkn/compiled_gradient.hpp>
//   #include <erkn/erkn.hpp>
//
//   // Duffing (the paper's problem 2): M = 100, grad U = -k^2 (2 q^3 - q), k = 0.03.
//   int main() {
//     erkn::System sys;  // (no sys.gradient: the functor is the gradient)
//     sys.M = erkn::Stiffness::scalar(100);
//     auto grad = [](const auto& q, auto& g) {
//       for (Eigen::Index i = 0; i < q.size(); ++i) g[i] = -9e-4 * (2 * q[i] * q[i] * q[i] - q[i]);
//     };
//     const erkn::Method& method = erkn::Method::by_name("SABA2");
//     const Eigen::VectorXd q0 = Eigen::VectorXd::Zero(1), p0 = Eigen::VectorXd::Constant(1, 10);
//     erkn::Integrator run = erkn::make_integrator(method, sys, grad, 0.01, q0, p0);
//     run.integrate(10.0);
//     // The same through System::gradient (a std::function): the same bits, slower at d <= 4.
//     sys.gradient = [&](const Eigen::VectorXd& q, Eigen::VectorXd& g) { grad(q, g); };
//     erkn::Integrator callback(method, sys, 0.01, q0, p0);
//     callback.integrate(10.0);
//     const bool same = run.q() == callback.q() && run.p() == callback.p();
//     std::printf("q(10) = %.17g; the callback's the same: %s\n", run.q()[0], same ? "yes" : "no");
//     return same ? 0 : 1;
//   }
//
// The functor is called as gradient(q, g) with q and g Eigen column vectors of doubles of the
// system's dimension: Eigen::Matrix<double, D, 1, Eigen::DontAlign> (D = 1..4) inside the compiled
// steps of a fixed dimension, Eigen::Map<const Eigen::VectorXd> and Eigen::Map<Eigen::VectorXd>
// in those of a half-spectrum basis, Eigen::VectorXd elsewhere, so write it as a template (or a
// generic lambda); g arrives sized. It is instantiated for every D up to 4 whatever the dimension,
// so it must compile for each. A functor of up to 8 bytes keeps the stepper of d = 4 within a block
// glibc's per-thread cache serves (1032 bytes; larger ones work, their constructions cost more).
//
// A functor (class) with a member hessian_vector(q, v, hv) as well, hv = Hess U(q) v on the same
// vectors (hv arrives sized), gives the Hessian-vector product of modified kicks (force-gradient
// methods: G = 2 Hess U grad U) too: the compiled steps call it inlined, and make_integrator sets
// System::hessian_vector_product to call it (which must then be empty), as it does the gradient.
// (problems/src/potentials.cpp's potentials are written so.)
//
// The installed package has the runtime's stepper headers under erkn/detail/.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <utility>

#include "erkn/error.hpp"
#include "erkn/integrator.hpp"
#if __has_include("detail/explicit_stepper.hpp")  // (installed)
#include "detail/explicit_stepper.hpp"
#include "detail/transforms.hpp"
#else  // (the source tree)
#include "../../src/explicit_stepper.hpp"
#include "../../src/transforms.hpp"
#endif

namespace erkn {
namespace detail {

/// The explicit steppers of d = 1..kFixedMaxD in the identity eigenbasis, and of any d in a
/// half-spectrum basis, with G compiled in.
template <class G>
class CompiledStepperSet final : public CompiledSteppers {
 public:
  explicit CompiledStepperSet(G gradient) : gradient_(std::move(gradient)) {}

  std::unique_ptr<StepperBase> make(bool diagonal, const Method& method, System&& system, double h,
                                    const Options& options, const Eigen::VectorXd& lambda,
                                    Eigen::Index d) const override {
    if (diagonal) return make_for<Eigen::ArrayXd>(method, std::move(system), h, options, lambda, d);
    return make_for<double>(method, std::move(system), h, options, lambda, d);
  }
  std::unique_ptr<StepperBase> make_half_spectrum(const Method& method, System&& system, double h,
                                                  const Options& options,
                                                  const std::vector<GridAxis>& axes,
                                                  const Eigen::VectorXd& lambda,
                                                  Eigen::Index d) const override {
    using Gradient = CompiledGradient<G, Eigen::Dynamic>;
    using Stepper =
        ExplicitStepper<HalfSpectrumTransform, Eigen::ArrayXd, Eigen::Dynamic, Gradient>;
    return std::make_unique<Stepper>(method, std::move(system), h, options,
                                     HalfSpectrumTransform(axes), lambda, d, Gradient{gradient_});
  }

 private:
  template <class Coef, int D = 1>
  std::unique_ptr<StepperBase> make_for(const Method& method, System&& system, double h,
                                        const Options& options, const Eigen::VectorXd& lambda,
                                        Eigen::Index d) const {
    if constexpr (D > kFixedMaxD) {
      throw Error("compiled gradient: no compiled stepper for dimension " + std::to_string(d));
    } else {
      using Stepper = ExplicitStepper<IdentityTransform, Coef, D, CompiledGradient<G, D>>;
      if (d == D)
        return std::make_unique<Stepper>(method, std::move(system), h, options, IdentityTransform{},
                                         lambda, d, CompiledGradient<G, D>{gradient_});
      return make_for<Coef, D + 1>(method, std::move(system), h, options, lambda, d);
    }
  }

  G gradient_;
};

}  // namespace detail

/// An Integrator as Integrator(method, system, h, q0, p0, options, t0) with `gradient` as
/// grad U (see above): System::gradient must be empty (erkn::Error otherwise) and becomes a call
/// of `gradient`, and so does System::hessian_vector_product of its hessian_vector when it has
/// one; explicit methods at d <= 4 with M's identity eigenbasis, and with circulant M or a
/// periodic grid in FFTW's half spectrum, step with it inlined.
template <class G>
Integrator make_integrator(const Method& method, System system, G gradient, double h,
                           const Eigen::VectorXd& q0, const Eigen::VectorXd& p0,
                           const Options& options = {}, double t0 = 0) {
  using Vector = Eigen::VectorXd;
  constexpr bool kProduct = requires(const G& f, const Vector& x, Vector& y) {
    f.hessian_vector(x, x, y);
  };
  if (system.gradient)
    throw Error(
        "make_integrator: System::gradient is set as well as the compiled gradient; "
        "give one of them");
  if (kProduct && system.hessian_vector_product)
    throw Error(
        "make_integrator: System::hessian_vector_product is set as well as the compiled "
        "gradient's hessian_vector; give one of them");
  system.gradient = [gradient](const Vector& q, Vector& g) { gradient(q, g); };
  if constexpr (kProduct)
    system.hessian_vector_product = [gradient](const Vector& q, const Vector& v, Vector& hv) {
      hv.resize(q.size());
      gradient.hessian_vector(q, v, hv);
    };
  return Integrator(method, std::move(system), h, q0, p0, options, t0,
                    std::make_shared<const detail::CompiledStepperSet<G>>(std::move(gradient)));
}

}  // namespace erkn
