#include "m_operator.hpp"

#include <cmath>

namespace erkn::detail {

MOperator::MOperator(const Stiffness& M, Eigen::Index d) : M_(M) {
  if (M.structure() != Stiffness::Structure::circulant) return;
  if (double(M.nonzeros().size()) <= 2 * std::log2(double(d))) return;
  fft_.emplace(d);
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

}  // namespace erkn::detail
