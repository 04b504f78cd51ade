// The nonlinear parts U of the problems, for any dimension (also the Python module's built-in
// potentials): each with its gradient and Hessian, written once here.
#include <cmath>
#include <erkn/compiled_gradient.hpp>
#include <memory>

#include "erkn/problems.hpp"

namespace erkn::problems {
namespace {

// The gradients, each written once as a functor of the vector types: Eigen::VectorXd for grad_u,
// the fixed-size vectors of the steppers it is compiled into (compiled_grad_u) for d <= 4.

// grad U = kappa sin q (kappa = 1, the paper's problem: no multiplication).
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
};

// grad U = c (2 q^3 - q), c = -k^2. (A loop, not an Eigen expression: at d = 1 the expression's
// size and alignment logic cost more than its arithmetic, which is the same per entry: cube()
// multiplies q q, then q.)
struct DuffingGradient {
  double c;
  template <class Q, class G>
  void operator()(const Q& q, G& g) const {
    const double* __restrict x = q.data();
    double* __restrict y = g.data();
    for (Eigen::Index i = 0; i < q.size(); ++i) y[i] = c * (2 * (x[i] * x[i] * x[i]) - x[i]);
  }
};

// grad U = beta q^3.
struct QuarticGradient {
  double beta;
  template <class Q, class G>
  void operator()(const Q& q, G& g) const {
    g = beta * q.array().cube();
  }
};

// u's grad_u and compiled_grad_u from one functor (grad_u sizes g first; the compiled steps
// hand it sized).
template <class G>
void set_gradient(Potential& u, G gradient) {
  u.grad_u = [gradient](const Vec& q, Vec& g) {
    g.resize(q.size());
    gradient(q, g);
  };
  u.compiled_grad_u = std::make_shared<const detail::CompiledStepperSet<G>>(gradient);
}

}  // namespace

Potential sine_potential(double kappa) {
  Potential u;
  set_gradient(u, SineGradient{kappa});
  u.potential = [kappa](const Vec& q) { return -kappa * q.array().cos().sum(); };
  u.hessian_u = [kappa](const Vec& q) {
    return Eigen::MatrixXd((kappa * q.array().cos()).matrix().asDiagonal());
  };
  u.hessian_vector_u = [kappa](const Vec& q, const Vec& v, Vec& hv) {
    hv = kappa * q.array().cos() * v.array();
  };
  return u;
}

// q'' + M q = k^2 (2q^3 - q)  <=>  U(q) = -k^2 sum (q^4 - q^2) / 2.
Potential duffing_potential(double k) {
  const double k2 = k * k;
  Potential u;
  set_gradient(u, DuffingGradient{-k2});
  u.potential = [k2](const Vec& q) {
    return -0.5 * k2 * (q.array().square().square() - q.array().square()).sum();
  };
  u.hessian_u = [k2](const Vec& q) {
    return Eigen::MatrixXd((-k2 * (6 * q.array().square() - 1)).matrix().asDiagonal());
  };
  u.hessian_vector_u = [k2](const Vec& q, const Vec& v, Vec& hv) {
    hv = -k2 * (6 * q.array().square() - 1) * v.array();
  };
  return u;
}

Potential quartic_potential(double beta) {
  Potential u;
  set_gradient(u, QuarticGradient{beta});
  u.potential = [beta](const Vec& q) { return 0.25 * beta * q.array().square().square().sum(); };
  u.hessian_u = [beta](const Vec& q) {
    return Eigen::MatrixXd((3 * beta * q.array().square()).matrix().asDiagonal());
  };
  u.hessian_vector_u = [beta](const Vec& q, const Vec& v, Vec& hv) {
    hv = 3 * beta * q.array().square() * v.array();
  };
  return u;
}

}  // namespace erkn::problems
