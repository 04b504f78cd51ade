// erkn::mode_energies (erkn/advisor.hpp).
#include <algorithm>

#include "erkn/advisor.hpp"
#include "erkn/error.hpp"
#include "grid_backend.hpp"

namespace erkn {
namespace {

using detail::GridBackend;

// 1/2 w (y_p^2 + lambda y_q^2) per coordinate: y_q, y_p the eigen coordinates of q and p, w the
// Parseval weights of the transform (1 for an orthonormal one).
Eigen::ArrayXd coordinate_energies(const Eigen::ArrayXd& yq, const Eigen::ArrayXd& yp,
                                   const Eigen::ArrayXd& lambda, const Eigen::ArrayXd& w) {
  return 0.5 * w * (yp.square() + lambda * yq.square());
}

// Grid axes' real transform (halfcomplex for periodic axes): eigen coordinates of q and p, and
// the tensor product of the axes' Parseval weights (row-major, as Stiffness::eigenvalues()).
void grid_coordinates(const std::vector<GridAxis>& axes, const Eigen::VectorXd& q,
                      const Eigen::VectorXd& p, Eigen::ArrayXd& yq, Eigen::ArrayXd& yp,
                      Eigen::ArrayXd& w) {
  const std::unique_ptr<GridBackend> backend = detail::make_grid_backend(axes);
  yq.resize(q.size()), yp.resize(p.size());
  backend->forward(q.data(), yq.data());
  backend->forward(p.data(), yp.data());
  w = Eigen::ArrayXd::Ones(1);
  for (const GridAxis& axis : axes) {
    const Eigen::ArrayXd a = detail::axis_weights(axis);
    Eigen::ArrayXd next(w.size() * axis.n);
    for (Eigen::Index i = 0; i < w.size(); ++i) next.segment(i * axis.n, axis.n) = w[i] * a;
    w.swap(next);
  }
}

}  // namespace

Eigen::VectorXd mode_energies(const Stiffness& M, const Eigen::VectorXd& q,
                              const Eigen::VectorXd& p) {
  if (q.size() == 0 || q.size() != p.size() || (M.dim() != 0 && M.dim() != q.size()) ||
      !q.allFinite() || !p.allFinite())
    throw Error("mode_energies: q and p must be finite, of one size d > 0 = the size of M");
  const Eigen::VectorXd& lambda = M.eigenvalues();
  const Eigen::ArrayXd one = Eigen::ArrayXd::Ones(q.size());
  switch (M.structure()) {
    case Stiffness::Structure::scalar:
      return Eigen::VectorXd::Constant(1, 0.5 * (p.squaredNorm() + lambda[0] * q.squaredNorm()));
    case Stiffness::Structure::diagonal:
      return coordinate_energies(q.array(), p.array(), lambda.array(), one).matrix();
    case Stiffness::Structure::dense: {
      const Eigen::MatrixXd& E = M.eigenvectors();
      const Eigen::ArrayXd yq = E.transpose() * q, yp = E.transpose() * p;
      return coordinate_energies(yq, yp, lambda.array(), one).matrix();
    }
    case Stiffness::Structure::grid: {
      Eigen::ArrayXd yq, yp, w;
      grid_coordinates(M.axes(), q, p, yq, yp, w);
      return coordinate_energies(yq, yp, lambda.array(), w).matrix();
    }
    case Stiffness::Structure::circulant: {
      // One periodic axis: coordinate k of the halfcomplex order has wave number min(k, N - k).
      const Eigen::Index n = q.size();
      Eigen::ArrayXd yq, yp, w, lambda_k(n);
      grid_coordinates({{n, 1.0, GridAxis::Boundary::periodic}}, q, p, yq, yp, w);
      for (Eigen::Index k = 0; k < n; ++k) lambda_k[k] = lambda[std::min(k, n - k)];
      const Eigen::ArrayXd e = coordinate_energies(yq, yp, lambda_k, w);
      Eigen::VectorXd out = Eigen::VectorXd::Zero(lambda.size());
      for (Eigen::Index k = 0; k < n; ++k) out[std::min(k, n - k)] += e[k];
      return out;
    }
  }
  throw Error("mode_energies: unknown structure of M");
}

}  // namespace erkn
