#include "grid_backend.hpp"

#include <cmath>
#include <numbers>

#include "erkn/error.hpp"

#ifndef ERKN_WITH_FFTW
#include <unsupported/Eigen/FFT>
#endif

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

Eigen::Index half_spectrum_size(const std::vector<GridAxis>& axes) {
  Eigen::Index m = axes.back().n / 2 + 1;
  for (std::size_t a = 0; a + 1 < axes.size(); ++a) m *= axes[a].n;
  return m;
}

Eigen::ArrayXd half_spectrum_weights(Eigen::Index n, Eigen::Index m) {
  const Eigen::Index half = n / 2 + 1;
  const double d = double(m / half) * double(n);
  Eigen::ArrayXd w = Eigen::ArrayXd::Constant(m, 2 / d);
  for (Eigen::Index row = 0; row < m; row += half) {
    w[row] = 1 / d;
    if (n % 2 == 0) w[row + n / 2] = 1 / d;
  }
  return w;
}

Eigen::VectorXd half_spectrum_eigenvalues(const std::vector<GridAxis>& axes, double shift) {
  // Built one axis at a time (row-major), as Stiffness::grid does over the whole spectrum.
  Eigen::ArrayXd lambda = Eigen::ArrayXd::Constant(1, shift);
  for (const GridAxis& axis : axes) {
    const bool last = &axis == &axes.back();
    const Eigen::ArrayXd mu = axis.eigenvalues().head(last ? axis.n / 2 + 1 : axis.n).array();
    Eigen::ArrayXd next(lambda.size() * mu.size());
    for (Eigen::Index i = 0; i < lambda.size(); ++i)
      next.segment(i * mu.size(), mu.size()) = mu + lambda[i];
    lambda.swap(next);
  }
  return lambda.max(0.0).matrix();  // (round-off negatives, as Stiffness::grid's)
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

BoundTransform HalfSpectrumBackend::bind_forward(const double* x, std::complex<double>* y) {
  return {[](void* backend, const void* in, void* out) {
            static_cast<HalfSpectrumBackend*>(backend)->forward(
                static_cast<const double*>(in), static_cast<std::complex<double>*>(out));
          },
          this, x, y};
}

BoundTransform HalfSpectrumBackend::bind_inverse_staged(double* x) {
  return {[](void* backend, const void*, void* out) {
            static_cast<HalfSpectrumBackend*>(backend)->inverse_staged(static_cast<double*>(out));
          },
          this, staging(), x};
}

std::unique_ptr<GridBackend> make_separable_backend(const std::vector<GridAxis>& axes) {
  return std::make_unique<SeparableBackend>(axes);
}

#ifndef ERKN_WITH_FFTW
std::unique_ptr<GridBackend> make_grid_backend(const std::vector<GridAxis>& axes) {
  return make_separable_backend(axes);
}
bool grid_backend_is_fftw() { return false; }

namespace {

// One periodic axis through Eigen's FFT (kissfft; its inverse divides by n).
class EigenHalfSpectrum final : public HalfSpectrumBackend {
 public:
  explicit EigenHalfSpectrum(Eigen::Index n) : n_(n) {
    fft_.SetFlag(Eigen::FFT<double>::HalfSpectrum);
  }
  void forward(const double* x, std::complex<double>* y) override { fft_.fwd(y, x, n_); }
  void inverse(const std::complex<double>* y, double* x) override { fft_.inv(x, y, n_); }
  std::complex<double>* staging() override { return staged_.data(); }
  double staging_scale() const override { return 1; }
  void inverse_staged(double* x) override { inverse(staged_.data(), x); }
  bool inverse_scaled(std::complex<double>* y, double* x) override {
    inverse(y, x);
    return true;
  }

 private:
  Eigen::Index n_;
  Eigen::FFT<double> fft_;
  Eigen::VectorXcd staged_ = Eigen::VectorXcd(n_ / 2 + 1);
};

}  // namespace

bool half_spectrum_available(const std::vector<GridAxis>& axes) {
  return axes.size() == 1 && axes[0].boundary == GridAxis::Boundary::periodic && axes[0].n >= 4;
}

std::unique_ptr<HalfSpectrumBackend> make_half_spectrum_backend(const std::vector<GridAxis>& axes) {
  if (!half_spectrum_available(axes)) throw Error("no real-to-complex transform for these axes");
  return std::make_unique<EigenHalfSpectrum>(axes[0].n);
}
#endif

}  // namespace erkn::detail
