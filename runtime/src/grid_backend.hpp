// The separable real transforms that diagonalise a grid M (Stiffness::grid): per axis the real
// FFT in halfcomplex order (periodic), DST-I (Dirichlet) or DCT-II (Neumann), applied along every
// axis of a row-major n_0 x ... x n_{k-1} array. forward is unnormalised, with FFTW's
// conventions (FFTW_R2HC, FFTW_RODFT00, FFTW_REDFT10); inverse is its exact inverse.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "erkn/stiffness.hpp"

namespace erkn::detail {

class GridBackend {
 public:
  virtual ~GridBackend() = default;
  /// y = F x; x and y hold d doubles and may not overlap. x is not changed.
  virtual void forward(const double* x, double* y) = 0;
  /// x = F^{-1} y; y is not changed.
  virtual void inverse(const double* y, double* x) = 0;
};

/// The 1-D forward matrix of an axis (n x n), FFTW's unnormalised definition of its kind.
Eigen::MatrixXd axis_forward_matrix(const GridAxis& axis);
/// Weights w with |x|^2 = sum_k w_k y_k^2 for y = the axis's forward transform of x.
Eigen::ArrayXd axis_weights(const GridAxis& axis);

/// Per axis a dense n_a x n_a matrix applied along the axis: O(d sum_a n_a), no FFT library.
std::unique_ptr<GridBackend> make_separable_backend(const std::vector<GridAxis>& axes);
/// FFTW when erkn is built with it (ERKN_WITH_FFTW), else the separable backend.
std::unique_ptr<GridBackend> make_grid_backend(const std::vector<GridAxis>& axes);
/// True when make_grid_backend uses FFTW.
bool grid_backend_is_fftw();

}  // namespace erkn::detail
