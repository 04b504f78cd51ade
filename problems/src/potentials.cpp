// The nonlinear parts U of the problems, for any dimension (also the Python module's built-in
// potentials): each with its gradient and Hessian, written once here.
#include <cmath>
#include <erkn/compiled_gradient.hpp>
#include <memory>

#include "erkn/problems.hpp"

namespace erkn::problems {
namespace {

// The gradients and Hessian-vector products (hessian_vector(q, v, hv): hv = Hess U(q) v, which
// modified kicks call), each written once as a functor of the vector types: Eigen::VectorXd for
// grad_u and hessian_vector_u, the vectors of the steppers they are compiled into
// (compiled_grad_u: fixed-size for d <= 4, maps in a half-spectrum basis).

// grad U = kappa sin q (kappa = 1, the paper's problem: no multiplication); Hess U v =
// kappa cos(q) v.
struct SineGradient {
  double kappa;
  template <class Q, class G>
  void operator()(const Q& q, G& g) const {
    if (kappa == 1) {
      g = q.array().sin();
    } else {
      g = kappa * q.array().sin();
    }
  }
  template <class Q, class V, class H>
  void hessian_vector(const Q& q, const V& v, H& hv) const {
    hv = kappa * q.array().cos() * v.array();
  }
};

// grad U = c (2 q^3 - q), c = -k^2; Hess U v = c (6 q^2 - 1) v. (Loops, not Eigen expressions:
// at d = 1 the expression's size and alignment logic cost more than its arithmetic, which is the
// same per entry: cube() multiplies q q, then q.)
struct DuffingGradient {
  double c;
  template <class Q, class G>
  void operator()(const Q& q, G& g) const {
    const double* __restrict x = q.data();
    double* __restrict y = g.data();
    for (Eigen::Index i = 0; i < q.size(); ++i) y[i] = c * (2 * (x[i] * x[i] * x[i]) - x[i]);
  }
  template <class Q, class V, class H>
  void hessian_vector(const Q& q, const V& v, H& hv) const {
    const double* __restrict x = q.data(), * __restrict w = v.data();
    double* __restrict y = hv.data();
    for (Eigen::Index i = 0; i < q.size(); ++i) y[i] = c * (6 * (x[i] * x[i]) - 1) * w[i];
  }
};

// grad U = beta q^3; Hess U v = 3 beta q^2 v.
struct QuarticGradient {
  double beta;
  template <class Q, class G>
  void operator()(const Q& q, G& g) const {
    g = beta * q.array().cube();
  }
  template <class Q, class V, class H>
  void hessian_vector(const Q& q, const V& v, H& hv) const {
    hv = 3 * beta * q.array().square() * v.array();
  }
};

// u's grad_u, hessian_vector_u and compiled_grad_u from one functor (grad_u and
// hessian_vector_u size their output first; the compiled steps hand it sized).
template <class G>
void set_derivatives(Potential& u, G gradient) {
  u.grad_u = [gradient](const Vec& q, Vec& g) {
    g.resize(q.size());
    gradient(q, g);
  };
  u.hessian_vector_u = [gradient](const Vec& q, const Vec& v, Vec& hv) {
    hv.resize(q.size());
    gradient.hessian_vector(q, v, hv);
  };
  u.compiled_grad_u = std::make_shared<const detail::CompiledStepperSet<G>>(gradient);
}

}  // namespace

Potential sine_potential(double kappa) {
  Potential u;
  set_derivatives(u, SineGradient{kappa});
  u.potential = [kappa](const Vec& q) { return -kappa * q.array().cos().sum(); };
  u.hessian_u = [kappa](const Vec& q) {
    return Eigen::MatrixXd((kappa * q.array().cos()).matrix().asDiagonal());
  };
  return u;
}

// q'' + M q = k^2 (2q^3 - q)  <=>  U(q) = -k^2 sum (q^4 - q^2) / 2.
Potential duffing_potential(double k) {
  const double k2 = k * k;
  Potential u;
  set_derivatives(u, DuffingGradient{-k2});
  u.potential = [k2](const Vec& q) {
    return -0.5 * k2 * (q.array().square().square() - q.array().square()).sum();
  };
  u.hessian_u = [k2](const Vec& q) {
    return Eigen::MatrixXd((-k2 * (6 * q.array().square() - 1)).matrix().asDiagonal());
  };
  return u;
}

Potential quartic_potential(double beta) {
  Potential u;
  set_derivatives(u, QuarticGradient{beta});
  u.potential = [beta](const Vec& q) { return 0.25 * beta * q.array().square().square().sum(); };
  u.hessian_u = [beta](const Vec& q) {
    return Eigen::MatrixXd((3 * beta * q.array().square()).matrix().asDiagonal());
  };
  return u;
}

}  // namespace erkn::problems
