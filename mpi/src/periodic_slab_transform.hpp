// The transforms into M's eigenbasis for a tensor grid whose axes are all periodic, distributed in
// slabs with FFTW-MPI's real-to-complex DFT (r2c / c2r). SlabTransform's halfcomplex r2r
// transforms have no SIMD codelets: one rank, 256^2, a transform pair cost 1167 us with
// FFTW_ESTIMATE and 754 us with FFTW_MEASURE against 345 us for r2c / c2r with FFTW_MEASURE (a
// stand-alone FFTW-MPI driver, best of 3 rounds). The forward transform ends transposed
// (FFTW_MPI_TRANSPOSED_OUT) and the inverse starts there, one all-to-all each, as in
// SlabTransform.
//
// The complex spectrum has the axes' sizes with the last halved, nc = (n_0, .., n_{K-1}/2 + 1);
// transposed, a rank holds rows first1.. of nc[1] and the rest whole: the local complex entry
// (k1 - first1, k0, k2, .., k_{K-1}) (row-major) is two spectral coordinates, its real and
// imaginary parts, each with the eigenvalue shift + mu_0[k0] + mu_1[k1] + .. (a periodic axis'
// mu[k] = mu[n - k]) and the norm weight prod_a 1/n_a, times 2 on the last axis except at
// k_{K-1} = 0 and n_{K-1}/2 (Parseval: those entries stand for X_k and X_{n-k}). Pointwise real
// functions of the eigenvalues keep the spectrum Hermitian, as c2r needs it.
#pragma once

#include <fftw3-mpi.h>
#include <mpi.h>

#include <Eigen/Core>
#include <vector>

#include "distributed_transform.hpp"
#include "erkn/stiffness.hpp"
#include "fftw_plans.hpp"

namespace erkn::mpi::detail {

/// True when M is a grid of two or more axes, all periodic (PeriodicSlabTransform applies).
bool all_periodic(const Stiffness& M);

/// FFTW-MPI's distribution of the r2c transform: physical rows first0.. of axis 0, complex
/// rows first1.. of nc[1], and the local buffer size (complex entries, with transpose room).
struct PeriodicSlabLayout {
  std::vector<ptrdiff_t> n, nc;  // the axes' sizes; the complex spectrum's
  ptrdiff_t rows0 = 0, first0 = 0, rows1 = 0, first1 = 0, buffer = 0;
  Eigen::Index physical_size = 0, spectral_size = 0;  // (spectral: two per complex entry)
};

/// The layout over comm (collective; M must satisfy all_periodic).
PeriodicSlabLayout periodic_slab_layout(MPI_Comm comm, const Stiffness& M);

class PeriodicSlabTransform final : public DistributedTransform {
 public:
  /// M must satisfy all_periodic (collective over comm).
  PeriodicSlabTransform(MPI_Comm comm, const Stiffness& M);
  /// Both parts of the local complex entry (k1 - first1, k0, k2, ..) are at entry
  /// (k0, k1, k2, ..) of M.eigenvalues().
  Eigen::Index mode(Eigen::Index local) const override;

 private:
  void execute_forward(const Eigen::Ref<const Eigen::VectorXd>& x,
                       Eigen::Ref<Eigen::ArrayXd> y) override;
  void execute_inverse_staged(Eigen::Ref<Eigen::VectorXd> x) override;
  // The physical slab's rows of the last axis (n_{K-1} values) in FFTW's padded real array.
  Eigen::Map<Eigen::ArrayXXd, 0, Eigen::OuterStride<>> padded();

  PeriodicSlabLayout layout_;
  FftwPlans<double> fftw_;  // in: the padded real array; out: the complex spectrum
};

}  // namespace erkn::mpi::detail
