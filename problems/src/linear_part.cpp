#include "erkn/problems/linear_part.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace erkn::problems {
namespace {

// out = shift q + sum_a (2 q_j - q_{j-1} - q_{j+1}) / spacing_a^2 along each axis, one line at a
// time (written independently of the runtime's stencil).
void apply_grid(const std::vector<GridAxis>& axes, double shift, const Vec& q, Vec& out) {
  const Eigen::Index d = q.size();
  out = shift * q;
  Eigen::Index stride = d;
  for (const GridAxis& a : axes) {
    stride /= a.n;
    const double w = 1 / (a.spacing * a.spacing);
    for (Eigen::Index i = 0; i < d; ++i) {
      const Eigen::Index j = (i / stride) % a.n;
      double left = 0, right = 0;  // q_{j-1}, q_{j+1} by the boundary rule
      if (j > 0)
        left = q[i - stride];
      else if (a.boundary == GridAxis::Boundary::periodic)
        left = q[i + (a.n - 1) * stride];
      else if (a.boundary == GridAxis::Boundary::neumann)
        left = q[i];
      if (j < a.n - 1)
        right = q[i + stride];
      else if (a.boundary == GridAxis::Boundary::periodic)
        right = q[i - (a.n - 1) * stride];
      else if (a.boundary == GridAxis::Boundary::neumann)
        right = q[i];
      out[i] += w * (2 * q[i] - left - right);
    }
  }
}

}  // namespace

Vec GridAxis::eigenvalues() const {
  const double pi = std::numbers::pi;
  Vec mu(n);
  for (int k = 0; k < n; ++k) {
    const double angle = boundary == Boundary::periodic    ? pi * std::min(k, n - k) / n
                         : boundary == Boundary::dirichlet ? pi * (k + 1) / (2.0 * (n + 1))
                                                           : pi * k / (2.0 * n);
    mu[k] = 4 / (spacing * spacing) * std::pow(std::sin(angle), 2);
  }
  return mu;
}

void LinearPart::apply(const Vec& q, Vec& out) const {
  switch (kind) {
    case Kind::scalar:
      out = omega2 * q;
      return;
    case Kind::diagonal:
      out = diag.cwiseProduct(q);
      return;
    case Kind::grid:
      apply_grid(axes, shift, q, out);
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
    case Kind::grid: {
      Vec lambda = Vec::Constant(1, shift);
      for (const GridAxis& a : axes) {
        const Vec mu = a.eigenvalues();
        Vec next(lambda.size() * a.n);
        for (Eigen::Index i = 0; i < lambda.size(); ++i)
          next.segment(i * a.n, a.n) = mu.array() + lambda[i];
        lambda.swap(next);
      }
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
