// The eigenbases of M. forward: physical x -> eigen coordinates; inverse: back. Functions of V
// act on eigen coordinates as coefficient-wise products; norm(y) is the 2-norm of inverse(y).
// None of them allocates after setup.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <complex>
#include <unsupported/Eigen/FFT>

namespace erkn::detail {

/// Scalar and diagonal M (and every RKN method): the eigenbasis is the standard basis.
struct IdentityTransform {
  using Spectral = Eigen::ArrayXd;
  Eigen::Index spectral_size(Eigen::Index d) const { return d; }
  void forward(const Eigen::VectorXd& x, Spectral& y) { y = x.array(); }
  void inverse(const Spectral& y, Eigen::VectorXd& x) { x = y.matrix(); }
  double norm(const Spectral& y) const { return y.matrix().norm(); }
};

/// Dense symmetric M = E diag(lambda) E^T: forward y = E^T x, inverse x = E y.
struct OrthogonalTransform {
  using Spectral = Eigen::ArrayXd;
  const Eigen::MatrixXd* E;
  Eigen::Index spectral_size(Eigen::Index d) const { return d; }
  void forward(const Eigen::VectorXd& x, Spectral& y) { y.matrix().noalias() = E->transpose() * x; }
  void inverse(const Spectral& y, Eigen::VectorXd& x) { x.noalias() = *E * y.matrix(); }
  double norm(const Spectral& y) const { return y.matrix().norm(); }
};

/// Symmetric circulant M: the real DFT (bins 0..N/2) diagonalises it.
struct RealFftTransform {
  using Spectral = Eigen::ArrayXcd;
  explicit RealFftTransform(Eigen::Index n) : n(n) {
    fft.SetFlag(Eigen::FFT<double>::HalfSpectrum);
  }
  Eigen::Index n;
  Eigen::FFT<double> fft;
  Eigen::Index spectral_size(Eigen::Index) const { return n / 2 + 1; }
  void forward(const Eigen::VectorXd& x, Spectral& y) { fft.fwd(y.data(), x.data(), n); }
  void inverse(const Spectral& y, Eigen::VectorXd& x) { fft.inv(x.data(), y.data(), n); }
  /// The 2-norm of the physical vector (Parseval; bins 1..ceil(N/2)-1 stand for two bins each).
  double norm(const Spectral& y) const {
    double sum = 2 * y.abs2().sum() - std::norm(y[0]);
    if (n % 2 == 0) sum -= std::norm(y[n / 2]);
    return std::sqrt(sum / double(n));
  }
};

}  // namespace erkn::detail
