// Solves (I + h^2 A (x) M) [x1; x2] = [r1; r2] for a 2x2 matrix A, in the eigenbasis of M:
// one 2x2 system per eigenvalue (identity basis for scalar/diagonal M, FFT for a circulant).
#pragma once

#include <Eigen/Core>
#include <complex>
#include <unsupported/Eigen/FFT>

#include "problem.hpp"

namespace ex {

class BlockSolve {
 public:
  BlockSolve(const LinearPart& m, int dim, double h, const Eigen::Matrix2d& a);
  /// In place: x1, x2 enter as r1, r2 and leave as the solution.
  void solve(Vec& x1, Vec& x2);

 private:
  bool fourier_;
  Vec i11_, i12_, i21_, i22_;  ///< entries of (I + h^2 lambda A)^{-1}, per eigenvalue
  Eigen::FFT<double> fft_;
  Eigen::VectorXcd y1_, y2_;
};

}  // namespace ex
