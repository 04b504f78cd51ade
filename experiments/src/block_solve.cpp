#include "block_solve.hpp"

#include <Eigen/LU>

namespace ex {

BlockSolve::BlockSolve(const LinearPart& m, int dim, double h, const Eigen::Matrix2d& a)
    : fourier_(m.kind == LinearPart::Kind::circulant) {
  const Vec lambda = m.eigenvalues(dim);
  i11_.resize(dim), i12_.resize(dim), i21_.resize(dim), i22_.resize(dim);
  for (int k = 0; k < dim; ++k) {
    const Eigen::Matrix2d inv = (Eigen::Matrix2d::Identity() + h * h * lambda[k] * a).inverse();
    i11_[k] = inv(0, 0), i12_[k] = inv(0, 1), i21_[k] = inv(1, 0), i22_[k] = inv(1, 1);
  }
}

void BlockSolve::solve(Vec& x1, Vec& x2) {
  if (!fourier_) {
    for (Eigen::Index k = 0; k < x1.size(); ++k) {
      const double r1 = x1[k];
      x1[k] = i11_[k] * r1 + i12_[k] * x2[k];
      x2[k] = i21_[k] * r1 + i22_[k] * x2[k];
    }
    return;
  }
  fft_.fwd(y1_, x1);
  fft_.fwd(y2_, x2);
  for (Eigen::Index k = 0; k < y1_.size(); ++k) {
    const std::complex<double> r1 = y1_[k];
    y1_[k] = i11_[k] * r1 + i12_[k] * y2_[k];
    y2_[k] = i21_[k] * r1 + i22_[k] * y2_[k];
  }
  fft_.inv(x1, y1_);
  fft_.inv(x2, y2_);
}

}  // namespace ex
