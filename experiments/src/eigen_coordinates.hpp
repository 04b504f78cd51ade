// Coordinates in which M of q'' + Mq = -grad U(q) is diagonal, for the exact-flow peers: the
// identity for scalar and diagonal M; for a symmetric circulant M the real FFT, whose half
// spectrum (N/2 + 1 complex numbers) is stored as 2(N/2 + 1) reals, each entry of a pair with the
// eigenvalue lambda_k of its frequency k. The forward map is unscaled, the inverse scales by 1/N,
// so from(to(x)) = x; any invertible map serves, since the kicks are transformed with it too.
// A grid M: FFTW's separable r2r transform (R2HC / RODFT00 / REDFT10 per axis, matching
// GridAxis::eigenvalues), one real coordinate per unknown; needs FFTW (else std::runtime_error).
#pragma once

#include <Eigen/Core>
#include <complex>
#include <memory>
#include <unsupported/Eigen/FFT>

#include "problem.hpp"

namespace ex {

class EigenCoordinates {
 public:
  EigenCoordinates(const LinearPart& m, int dim);
  ~EigenCoordinates();
  /// Number of real coordinates (dim, or 2(dim/2 + 1) for a circulant).
  Eigen::Index size() const { return lambda_.size(); }
  /// The eigenvalue of M belonging to each real coordinate.
  const Vec& lambda() const { return lambda_; }
  /// y = T x (physical -> eigen coordinates); y is resized.
  void to(const Vec& x, Vec& y);
  /// x = T^{-1} y (eigen -> physical coordinates); x is resized.
  void from(const Vec& y, Vec& x);

 private:
  int dim_;
  bool fourier_;
  Vec lambda_;
  Eigen::FFT<double> fft_;
  struct GridPlans;
  std::unique_ptr<GridPlans> grid_;
};

}  // namespace ex
