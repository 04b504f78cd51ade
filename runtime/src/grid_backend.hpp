// The separable real transforms that diagonalise a grid M (Stiffness::grid): per axis the real
// FFT in halfcomplex order (periodic), DST-I (Dirichlet) or DCT-II (Neumann), applied along every
// axis of a row-major n_0 x ... x n_{k-1} array. forward is unnormalised, with FFTW's
// conventions (FFTW_R2HC, FFTW_RODFT00, FFTW_REDFT10); inverse is its exact inverse.
#pragma once

#include <Eigen/Core>
#include <complex>
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

/// A transform bound to its input and output arrays: operator() computes it through one plain
/// indirect call, run(plan, in, out) (FFTW: the plan executed straight on the arrays, whose
/// alignment was checked when they were bound).
struct BoundTransform {
  void (*run)(void* plan, const void* in, void* out) = nullptr;
  void* plan = nullptr;
  const void* in = nullptr;
  void* out = nullptr;
  void operator()() const { run(plan, in, out); }
};

/// The complex half spectrum of a grid whose axes are all periodic (a circulant M: one axis):
/// forward y = the unnormalised DFT X_k = sum_j x_j e^{-2 pi i k.j/n} at k_0..k_{K-2} = 0..n_a-1
/// and k_{K-1} = 0..n/2 (the other X_k are conj(X_{-k})), row-major, m = d / n (n/2 + 1) of
/// them; inverse is its exact inverse and reads only what a real x can produce (the imaginary
/// parts that must vanish are ignored). Real to complex: FFTW's r2c/c2r, whose SIMD codelets
/// halfcomplex r2r lacks.
class HalfSpectrumBackend {
 public:
  virtual ~HalfSpectrumBackend() = default;
  /// y = F x; x holds d doubles, y m complex numbers; they may not overlap. x is not changed.
  virtual void forward(const double* x, std::complex<double>* y) = 0;
  /// x = F^{-1} y; y is not changed.
  virtual void inverse(const std::complex<double>* y, double* x) = 0;
  /// The buffer (m complex numbers) inverse_staged transforms: a pass that writes y there,
  /// scaled by staging_scale(), spares inverse its own copy of y.
  virtual std::complex<double>* staging() = 0;
  virtual double staging_scale() const = 0;
  /// x = F^{-1} y from y staged as above; the staging buffer's contents are lost.
  virtual void inverse_staged(double* x) = 0;
  /// x = F^{-1} y from y scaled as a staged y is, in an array of the caller's (m complex numbers,
  /// not the staging buffer), whose contents are lost. Returns whether the staging buffer's are
  /// kept (false: y went through it).
  virtual bool inverse_scaled(std::complex<double>* y, double* x) = 0;
  /// forward(x, y) and inverse_staged(x) bound to these arrays (a stepper transforms the same
  /// ones at every gradient: no virtual call or alignment check per transform). By default the
  /// bound transform calls the virtual one.
  virtual BoundTransform bind_forward(const double* x, std::complex<double>* y);
  virtual BoundTransform bind_inverse_staged(double* x);
};

/// True when every axis is periodic and, without FFTW, there is one axis of n >= 4 (Eigen's
/// real FFT: of size 1 it crashed, found by the API fuzz).
bool half_spectrum_available(const std::vector<GridAxis>& axes);
/// FFTW's r2c/c2r, or without FFTW Eigen's real FFT; throws unless half_spectrum_available.
std::unique_ptr<HalfSpectrumBackend> make_half_spectrum_backend(const std::vector<GridAxis>& axes);
/// The number m of half-spectrum coordinates.
Eigen::Index half_spectrum_size(const std::vector<GridAxis>& axes);
/// Weights w with |x|^2 = sum_k w_k |y_k|^2 (Parseval): 1/d where X_k is its own conjugate's
/// partner (k_{K-1} = 0, or n/2 for even n), else 2/d (X_k stands for X_k and X_{-k}).
/// n: the last axis's points, m: half_spectrum_size.
Eigen::ArrayXd half_spectrum_weights(Eigen::Index n, Eigen::Index m);
/// The eigenvalue shift + sum_a mu_a(k_a) of each coordinate (GridAxis::eigenvalues: wave number
/// k_a and n_a - k_a share one).
Eigen::VectorXd half_spectrum_eigenvalues(const std::vector<GridAxis>& axes, double shift);

}  // namespace erkn::detail
