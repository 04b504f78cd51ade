#include "m_operator.hpp"

#include <cmath>

namespace erkn::detail {

MOperator::MOperator(const Stiffness& M, Eigen::Index d) : M_(M) {
  // (The stencil's test first: the axis, a vector, was an allocation per explicit stepper.)
  if (M.structure() != Stiffness::Structure::circulant ||
      double(M.nonzeros().size()) <= 2 * std::log2(double(d)))
    return;
  const std::vector<GridAxis> axis{{d, 1.0, GridAxis::Boundary::periodic}};
  if (!half_spectrum_available(axis)) return;
  fft_ = std::make_unique<HalfSpectrumTransform>(axis);
  spectrum_.resize(d / 2 + 1);
}

void MOperator::apply(const Eigen::VectorXd& x, Eigen::VectorXd& y) {
  switch (M_.structure()) {
    case Stiffness::Structure::scalar:
      y = M_.entries()[0] * x;
      return;
    case Stiffness::Structure::diagonal:
      y = M_.entries().cwiseProduct(x);
      return;
    case Stiffness::Structure::dense:
      y.noalias() = M_.matrix() * x;
      return;
    case Stiffness::Structure::grid:
      apply_grid(x, y);
      return;
    case Stiffness::Structure::circulant:
      if (fft_) {
        fft_->forward(x, spectrum_);
        spectrum_ *= M_.eigenvalues().array();
        fft_->inverse(spectrum_, y);
        return;
      }
      // y_i = sum_j col[j] x[(i - j) mod N] over the nonzeros j of the first column.
      const Eigen::Index n = x.size();
      y.setZero();
      for (int j : M_.nonzeros()) {
        const double c = M_.entries()[j];
        y.tail(n - j) += c * x.head(n - j);
        y.head(j) += c * x.tail(j);
      }
      return;
  }
}

// y = shift x + sum_a (-D2_a) x. Along axis a each outer block of the row-major array is an
// inner x n column-major matrix X whose column j is the line index j; the stencil
// (2 x_j - x_{j-1} - x_{j+1}) / spacing^2 acts on whole columns, the ends by the boundary rule.
void MOperator::apply_grid(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  const Eigen::Index d = x.size();
  y = M_.shift() * x;
  Eigen::Index inner = d;
  for (const GridAxis& axis : M_.axes()) {
    const Eigen::Index n = axis.n;
    inner /= n;
    const double w = 1 / (axis.spacing * axis.spacing);
    for (Eigen::Index o = 0; o < d / (n * inner); ++o) {
      Eigen::Map<const Eigen::MatrixXd> X(x.data() + o * n * inner, inner, n);
      Eigen::Map<Eigen::MatrixXd> Y(y.data() + o * n * inner, inner, n);
      Y += (2 * w) * X;
      Y.rightCols(n - 1) -= w * X.leftCols(n - 1);
      Y.leftCols(n - 1) -= w * X.rightCols(n - 1);
      switch (axis.boundary) {
        case GridAxis::Boundary::periodic:
          Y.col(0) -= w * X.col(n - 1);
          Y.col(n - 1) -= w * X.col(0);
          break;
        case GridAxis::Boundary::neumann:  // mirrored neighbours x_{-1} = x_0, x_n = x_{n-1}
          Y.col(0) -= w * X.col(0);
          Y.col(n - 1) -= w * X.col(n - 1);
          break;
        case GridAxis::Boundary::dirichlet:  // zero outside
          break;
      }
    }
  }
}

}  // namespace erkn::detail
