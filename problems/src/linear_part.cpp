#include "erkn/problems/linear_part.hpp"

#include <cmath>
#include <numbers>

namespace erkn::problems {

void LinearPart::apply(const Vec& q, Vec& out) const {
  switch (kind) {
    case Kind::scalar:
      out = omega2 * q;
      return;
    case Kind::diagonal:
      out = diag.cwiseProduct(q);
      return;
    case Kind::circulant: {
      // (Mq)_i = sum_j c_j q_{(i - j) mod n}, over the non-zero c_j, as two contiguous pieces.
      const Eigen::Index n = q.size();
      out.setZero(n);
      for (Eigen::Index j = 0; j < n; ++j) {
        if (column[j] == 0) continue;
        out.tail(n - j) += column[j] * q.head(n - j);
        out.head(j) += column[j] * q.tail(j);
      }
      return;
    }
  }
}

Vec LinearPart::eigenvalues(int dim) const {
  switch (kind) {
    case Kind::scalar:
      return Vec::Constant(dim, omega2);
    case Kind::diagonal:
      return diag;
    case Kind::circulant: {
      Vec lambda = Vec::Zero(dim);
      for (int k = 0; k < dim; ++k)
        for (int j = 0; j < dim; ++j)
          if (column[j] != 0) lambda[k] += column[j] * std::cos(2 * std::numbers::pi * j * k / dim);
      return lambda;
    }
  }
  return {};
}

Eigen::MatrixXd LinearPart::dense(int dim) const {
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(dim, dim);
  Vec e = Vec::Zero(dim), col(dim);
  for (int j = 0; j < dim; ++j) {
    e[j] = 1;
    apply(e, col);
    m.col(j) = col;
    e[j] = 0;
  }
  return m;
}

}  // namespace erkn::problems
