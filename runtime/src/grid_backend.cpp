#include "grid_backend.hpp"

#include <cmath>
#include <numbers>

namespace erkn::detail {

Eigen::MatrixXd axis_forward_matrix(const GridAxis& axis) {
  using std::numbers::pi;
  const Eigen::Index n = axis.n;
  Eigen::MatrixXd B(n, n);
  for (Eigen::Index k = 0; k < n; ++k)
    for (Eigen::Index j = 0; j < n; ++j) switch (axis.boundary) {
        case GridAxis::Boundary::periodic: {
          // Halfcomplex: Re X_k for k <= n/2, Im X_{n-k} for k > n/2, X_k = sum x_j e^{-2 pi i
          // jk/n}; the angle reduced exactly to (j w) mod n.
          const Eigen::Index w = std::min(k, n - k);
          const double angle = 2 * pi * double((j * w) % n) / double(n);
          B(k, j) = 2 * k <= n ? std::cos(angle) : -std::sin(angle);
          break;
        }
        case GridAxis::Boundary::dirichlet:
          B(k, j) = 2 * std::sin(pi * double((j + 1) * (k + 1)) / double(n + 1));
          break;
        case GridAxis::Boundary::neumann:
          B(k, j) = 2 * std::cos(pi * double((2 * j + 1) * k) / double(2 * n));
          break;
      }
  return B;
}

Eigen::ArrayXd axis_weights(const GridAxis& axis) {
  const Eigen::Index n = axis.n;
  switch (axis.boundary) {
    case GridAxis::Boundary::periodic: {
      // Parseval: bins 0 and n/2 count once, the others stand for X_k and X_{n-k}.
      Eigen::ArrayXd w = Eigen::ArrayXd::Constant(n, 2 / double(n));
      w[0] = 1 / double(n);
      if (n % 2 == 0) w[n / 2] = 1 / double(n);
      return w;
    }
    case GridAxis::Boundary::dirichlet:
      return Eigen::ArrayXd::Constant(n, 1 / double(2 * (n + 1)));
    case GridAxis::Boundary::neumann: {
      Eigen::ArrayXd w = Eigen::ArrayXd::Constant(n, 1 / double(2 * n));
      w[0] = 1 / double(4 * n);
      return w;
    }
  }
  return {};
}

namespace {

class SeparableBackend final : public GridBackend {
 public:
  explicit SeparableBackend(const std::vector<GridAxis>& axes) {
    d_ = 1;
    for (const GridAxis& axis : axes) {
      d_ *= axis.n;
      const Eigen::MatrixXd B = axis_forward_matrix(axis);
      forward_.push_back(B.transpose());  // (applied from the right to inner x n blocks)
      // B^{-1} = B^T diag(w), from B^T diag(w) B = I (axis_weights); transposed likewise.
      inverse_.push_back(axis_weights(axis).matrix().asDiagonal() * B);
    }
    a_.resize(d_);
    b_.resize(d_);
  }
  void forward(const double* x, double* y) override { apply(forward_, x, y); }
  void inverse(const double* y, double* x) override { apply(inverse_, y, x); }

 private:
  // y = (A_0 x ... x A_{k-1}) x: along axis a, each of the outer blocks is an inner x n matrix
  // (column-major view of the row-major array) multiplied from the right by A_a^T.
  void apply(const std::vector<Eigen::MatrixXd>& At, const double* x, double* y) {
    a_ = Eigen::Map<const Eigen::VectorXd>(x, d_);
    Eigen::Index inner = d_;
    for (const Eigen::MatrixXd& A : At) {
      const Eigen::Index n = A.rows();
      inner /= n;
      for (Eigen::Index o = 0; o < d_ / (n * inner); ++o) {
        Eigen::Map<Eigen::MatrixXd> from(a_.data() + o * n * inner, inner, n),
            to(b_.data() + o * n * inner, inner, n);
        to.noalias() = from * A;
      }
      a_.swap(b_);
    }
    Eigen::Map<Eigen::VectorXd>(y, d_) = a_;
  }

  Eigen::Index d_;
  std::vector<Eigen::MatrixXd> forward_, inverse_;
  Eigen::VectorXd a_, b_;  // ping-pong workspace
};

}  // namespace

std::unique_ptr<GridBackend> make_separable_backend(const std::vector<GridAxis>& axes) {
  return std::make_unique<SeparableBackend>(axes);
}

#ifndef ERKN_WITH_FFTW
std::unique_ptr<GridBackend> make_grid_backend(const std::vector<GridAxis>& axes) {
  return make_separable_backend(axes);
}
bool grid_backend_is_fftw() { return false; }
#endif

}  // namespace erkn::detail
