// The scenes erkn_integrate_benchmark and the specialist peer's tests run: a problem from the
// problems library (erkn's side calls its System, as a user would), the same gradient as an
// inlined functor for the specialist's loop (bench/specialist_peer.hpp), and the basis of M.
#pragma once

#include <Eigen/Core>
#include <erkn/problems.hpp>
#include <stdexcept>

#include "specialist_peer.hpp"

namespace bench {

/// grad U of the problems library's sine-Gordon scenes (kappa = 1): sin, pointwise.
struct SineGordonGradient {
  template <class Q, class G>
  void operator()(const Q& q, G& g) const {
    g = q.sin();
  }
};
/// grad U of Duffing (P2): -k^2 (2 q^3 - q).
struct DuffingGradient {
  double k2 = 0.03 * 0.03;
  template <class Q, class G>
  void operator()(const Q& q, G& g) const {
    g = -k2 * (2 * q.cube() - q);
  }
};
/// grad U of the stellar orbits (P3): U = -eps q1 q2^2.
struct StellarGradient {
  double eps = 1e-3;
  template <class Q, class G>
  void operator()(const Q& q, G& g) const {
    g[0] = -eps * q[1] * q[1];
    g[1] = -2 * eps * q[0] * q[1];
  }
};

/// A peer's gradient functor (on arrays) as erkn::make_integrator calls a compiled-in gradient (on
/// vectors).
template <class Gradient>
auto on_vectors(Gradient g) {
  return [g](const auto& q, auto& out) {
    auto a = out.array();
    g(q.array(), a);
  };
}
/// sys without its gradient: make_integrator's System, whose functor is the gradient.
inline erkn::System without_gradient(erkn::System sys) {
  sys.gradient = nullptr;
  return sys;
}

/// The specialist's basis of a problem's M: the identity (scalar, diagonal; D fixed) or FFTW r2c
/// (circulant, periodic 2-D grid).
template <int D>
specialist::IdentityBasis<D> identity_basis(const erkn::problems::LinearPart& m, int dim) {
  specialist::IdentityBasis<D> b;
  b.m = m.eigenvalues(dim).array();
  return b;
}
inline specialist::FourierBasis fourier_basis(const erkn::problems::LinearPart& m) {
  using Kind = erkn::problems::LinearPart::Kind;
  if (m.kind == Kind::circulant) return specialist::FourierBasis::circulant(m.column);
  using Boundary = erkn::problems::GridAxis::Boundary;
  if (m.kind == Kind::grid && m.axes.size() == 2 && m.axes[0].boundary == Boundary::periodic &&
      m.axes[1].boundary == Boundary::periodic)
    return specialist::FourierBasis::periodic_grid(m.axes[0].n, m.axes[1].n, m.axes[0].spacing,
                                                   m.axes[1].spacing, m.shift);
  throw std::invalid_argument("fourier_basis: M is neither circulant nor a 2-D periodic grid");
}

}  // namespace bench
