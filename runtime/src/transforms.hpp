// The eigenbases of M. forward: physical x -> eigen coordinates; inverse: back. Functions of V
// act on eigen coordinates as coefficient-wise products; squared_norm(y) is |inverse(y)|^2 (no
// square root: the stage solver's sums are squares).
// None of them allocates after setup. They take Eigen arrays, vectors and maps over them.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <complex>
#include <memory>
#include <numbers>
#include <vector>

#include "grid_backend.hpp"

namespace erkn::detail {

/// Scalar and diagonal M (and every RKN method): the eigenbasis is the standard basis.
struct IdentityTransform {
  using Spectral = Eigen::ArrayXd;
  Eigen::Index spectral_size(Eigen::Index d) const { return d; }
  template <class X, class Y>
  void forward(const X& x, Y&& y) {
    y = x.array();
  }
  template <class Y, class X>
  void inverse(const Y& y, X&& x) {
    x = y.matrix();
  }
  template <class Y>
  double squared_norm(const Y& y) const {
    return y.matrix().squaredNorm();
  }
};

/// Dense symmetric M = E diag(lambda) E^T: forward y = E^T x, inverse x = E y.
struct OrthogonalTransform {
  using Spectral = Eigen::ArrayXd;
  const Eigen::MatrixXd* E;
  Eigen::Index spectral_size(Eigen::Index d) const { return d; }
  template <class X, class Y>
  void forward(const X& x, Y&& y) {
    y.matrix().noalias() = E->transpose() * x;
  }
  template <class Y, class X>
  void inverse(const Y& y, X&& x) {
    x.noalias() = *E * y.matrix();
  }
  template <class Y>
  double squared_norm(const Y& y) const {
    return y.matrix().squaredNorm();
  }
};

/// Symmetric circulant M at small N: the real orthonormal Fourier basis, applied as explicit
/// matrix-vector products (closed form, no eigendecomposition). Eigen coordinates:
///   0..N/2          cos(2 pi j k / N), k = 0..N/2,        eigenvalue lambda_k
///   N/2+1..N-1      sin(2 pi j k / N), k = 1..ceil(N/2)-1, eigenvalue lambda_k again
/// scaled to unit norm (sqrt(1/N) for k = 0 and k = N/2, sqrt(2/N) otherwise). Cosines are even
/// and sines odd under j -> N - j, so a transform folds x into x_j +- x_{N-j} and needs only the
/// half-size blocks C (j, k = 0..N/2) and S (j, k = 1..ceil(N/2)-1): N^2/2 multiply-adds.
struct FourierBasisTransform {
  using Spectral = Eigen::ArrayXd;
  explicit FourierBasisTransform(Eigen::Index n)
      : n(n), nc(n / 2 + 1), ns((n - 1) / 2), C(nc, nc), S(ns, ns), even(nc), odd(ns) {
    // Angles reduced exactly to (j k) mod N, as for the eigenvalues in Stiffness::circulant.
    Eigen::ArrayXd cosine(n), sine(n);
    for (Eigen::Index m = 0; m < n; ++m) {
      cosine[m] = std::cos(2 * std::numbers::pi * double(m) / double(n));
      sine[m] = std::sin(2 * std::numbers::pi * double(m) / double(n));
    }
    const double edge = std::sqrt(1 / double(n)), inner = std::sqrt(2 / double(n));
    for (Eigen::Index k = 0; k < nc; ++k)
      for (Eigen::Index j = 0; j < nc; ++j)
        C(j, k) = ((k == 0 || 2 * k == n) ? edge : inner) * cosine[(j * k) % n];
    for (Eigen::Index k = 0; k < ns; ++k)
      for (Eigen::Index j = 0; j < ns; ++j) S(j, k) = inner * sine[((j + 1) * (k + 1)) % n];
  }
  /// The eigenvalue of each eigen coordinate from lambda_0..lambda_{N/2} (Stiffness::eigenvalues).
  static Eigen::VectorXd coordinate_eigenvalues(const Eigen::VectorXd& lambda, Eigen::Index n) {
    Eigen::VectorXd all(n);
    all.head(n / 2 + 1) = lambda;
    all.tail((n - 1) / 2) = lambda.segment(1, (n - 1) / 2);
    return all;
  }
  Eigen::Index n, nc, ns;
  Eigen::MatrixXd C, S;
  Eigen::VectorXd even, odd;  // workspace
  Eigen::Index spectral_size(Eigen::Index d) const { return d; }
  // even_j = x_j + x_{N-j} (x_j alone for j = 0 and j = N/2), odd_j = x_j - x_{N-j}.
  template <class X, class Y>
  void forward(const X& x, Y&& y) {
    even = x.head(nc);
    even.segment(1, ns) += x.tail(ns).reverse();
    odd = x.segment(1, ns) - x.tail(ns).reverse();
    y.head(nc).matrix().noalias() = C.transpose() * even;
    y.tail(ns).matrix().noalias() = S.transpose() * odd;
  }
  template <class Y, class X>
  void inverse(const Y& y, X&& x) {
    even.noalias() = C * y.head(nc).matrix();
    odd.noalias() = S * y.tail(ns).matrix();
    x.head(nc) = even;
    x.segment(1, ns) += odd;
    x.tail(ns) = (even.segment(1, ns) - odd).reverse();
  }
  template <class Y>
  double squared_norm(const Y& y) const {
    return y.matrix().squaredNorm();
  }
};

/// Circulant M (one periodic axis) and grid M whose axes are all periodic: the complex half
/// spectrum of grid_backend.hpp (FFTW's r2c/c2r, or Eigen's real FFT for one axis without FFTW).
/// Eigen coordinates are the DFT coefficients X_k, m = d / n (n/2 + 1) complex numbers (n: the
/// last axis's); X_k's eigenvalue is that of its wave numbers (circulant: lambda_k =
/// Stiffness::eigenvalues()[k]; grid: half_spectrum_eigenvalues), and the real coefficients of
/// the steppers act on the complex entries. Norms count each X_k once or twice (Parseval).
struct HalfSpectrumTransform {
  using Spectral = Eigen::ArrayXcd;
  /// Throws unless half_spectrum_available(axes).
  explicit HalfSpectrumTransform(const std::vector<GridAxis>& axes)
      : backend(make_half_spectrum_backend(axes)),
        m_(half_spectrum_size(axes)),
        n_(axes.back().n),
        staging_(reinterpret_cast<double*>(backend->staging())),
        staging_scale_(backend->staging_scale()) {}
  std::unique_ptr<HalfSpectrumBackend> backend;
  Eigen::Index spectral_size(Eigen::Index) const { return m_; }
  /// The Parseval weights (half_spectrum_weights), made at the first call: the explicit steppers
  /// never read them (at N = 8192 they were 8193 doubles written per construction).
  const Eigen::ArrayXd& weight() const {
    if (weight_.size() == 0) weight_ = half_spectrum_weights(n_, m_);
    return weight_;
  }
  /// (Through the transforms bound to the last three pairs of arrays: a stepper's gradients
  /// transform the same arrays every time, or two in turn when it keeps the last force (FSAL), and
  /// reading its state transforms two more.)
  template <class X, class Y>
  void forward(const X& x, Y&& y) {
    forward_(x.data(), y.data(), [&] { return backend->bind_forward(x.data(), y.data()); })();
  }
  template <class Y, class X>
  void inverse(const Y& y, X&& x) {
    backend->inverse(y.data(), x.data());
  }
  /// Where a pass may stage the eigen coordinates y (as doubles, re and im) times
  /// staging_scale() for inverse_staged, which then transforms them without a copy of its own.
  double* staging() { return staging_; }
  double staging_scale() const { return staging_scale_; }
  template <class X>
  void inverse_staged(X&& x) {
    inverse_staged_(staging_, x.data(), [&] { return backend->bind_inverse_staged(x.data()); })();
  }
  /// x = the physical vector of eigen coordinates y (m of them) already scaled by
  /// staging_scale(), as the staging buffer holds them; y is lost. Returns whether the staging
  /// buffer's contents are kept.
  template <class X>
  bool inverse_scaled(std::complex<double>* y, X&& x) {
    return backend->inverse_scaled(y, x.data());
  }
  /// The squared 2-norm of the physical vector.
  template <class Y>
  double squared_norm(const Y& y) const {
    return (weight() * y.abs2()).sum();
  }

 private:
  // The transforms bound to the last three pairs of arrays, replaced in turn.
  struct Bound {
    BoundTransform entry[3];
    int next = 0;
    // The binding of (in, out), or a new one from bind().
    template <class Bind>
    BoundTransform& operator()(const void* in, void* out, Bind&& bind) {
      for (BoundTransform& b : entry)
        if (b.run && b.in == in && b.out == out) return b;
      BoundTransform& b = entry[next];
      next = (next + 1) % 3;
      return b = bind();
    }
  };

  Eigen::Index m_, n_;             // half_spectrum_size, the last axis's points
  mutable Eigen::ArrayXd weight_;  // (none until weight())
  double* staging_;                // backend's staging buffer
  // Its scale, kept: the implicit stage's passes read it per iteration, where the backend's
  // virtual call and its division were ~1 % of the time (perf, sine-Gordon N = 32, SERKN4s6).
  double staging_scale_;
  Bound forward_, inverse_staged_;
};

/// Grid M (Stiffness::grid) with a Dirichlet or Neumann axis, or without FFTW: the separable real
/// transform of grid_backend.hpp. Eigen coordinates are real, d of them, in the transform's order
/// (row-major over the axes' coordinates k).
struct GridTransform {
  using Spectral = Eigen::ArrayXd;
  explicit GridTransform(const std::vector<GridAxis>& axes)
      : backend(make_grid_backend(axes)), weight(Eigen::ArrayXd::Ones(1)) {
    // Parseval weights of the unnormalised forward transform: a tensor product of the axes'.
    for (const GridAxis& axis : axes) {
      const Eigen::ArrayXd w = axis_weights(axis);
      Eigen::ArrayXd next(weight.size() * axis.n);
      for (Eigen::Index i = 0; i < weight.size(); ++i)
        next.segment(i * axis.n, axis.n) = weight[i] * w;
      weight.swap(next);
    }
  }
  std::unique_ptr<GridBackend> backend;
  Eigen::ArrayXd weight;
  Eigen::Index spectral_size(Eigen::Index d) const { return d; }
  template <class X, class Y>
  void forward(const X& x, Y&& y) {
    backend->forward(x.data(), y.data());
  }
  template <class Y, class X>
  void inverse(const Y& y, X&& x) {
    backend->inverse(y.data(), x.data());
  }
  template <class Y>
  double squared_norm(const Y& y) const {
    return (weight * y.square()).sum();
  }
};

}  // namespace erkn::detail
